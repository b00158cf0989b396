// SPDX-License-Identifier: Apache-2.0
// The effects panel: every parameter change renders off the GUI thread, the newest request
// wins, and what it shows equals a direct render of the same effect on the same thumbnail.
#include "core/effects/effect_table.h"
#include "core/pipeline/render.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/depth_commands.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/image_convert.h"
#include "ui/panels/effects_panel.h"

#include <QElapsedTimer>
#include <QSemaphore>
#include <QSignalSpy>
#include <QtTest/QtTest>

#include <atomic>
#include <cmath>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

bool waitForGeneration(EffectsPanel& panel, quint64 generation) {
  QSignalSpy spy(&panel, &EffectsPanel::previewReady);
  for (int i = 0; i < 200 && panel.previewGeneration() < generation; ++i) spy.wait(100);
  return panel.previewGeneration() == generation;
}

}  // namespace

class TestEffectsPanel : public QObject {
  Q_OBJECT

 private slots:
  void showsTheNewestSettings() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    panel.setEffect("colour-shift");
    // Rapid edits: only the last one may be shown.
    for (int i = 1; i <= 20; ++i) QVERIFY(panel.setParameter("s-red", 0.01 * i));
    QVERIFY(panel.setParameter("s-blue", -0.1));
    QVERIFY(!panel.setParameter("no-such", 1.0));
    const quint64 last = panel.requestedGeneration();
    QVERIFY(waitForGeneration(panel, last));
    QVERIFY2(panel.status().contains("splat"), qPrintable(panel.status()));

    const ImageF thumb = boxDownscale(doc.photo()->preview, 384);
    const FrameSize frame{thumb.width, thumb.height};
    const Artcam camera = buildEffect("colour-shift", panel.parameters(), frame);
    const QImage expected = qimageFromLinear(render(RenderInputs::of(thumb), camera));
    QCOMPARE(panel.preview().size(), expected.size());
    QVERIFY(panel.preview() == expected);
  }

  // The depth-of-field lens model is a panel parameter: thin-lens 0 reaches the camera as the
  // linear σ² = k²(d − f)²/f² (depth_of_field.h), checked at a few depths.
  void depthOfFieldOffersTheLinearModel() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    panel.setEffect("depth-of-field");
    QVERIFY(panel.parameters().count("thin-lens"));
    QCOMPARE(panel.parameters().at("thin-lens"), std::vector<double>{1.0});  // the thin lens by default
    QVERIFY(panel.setParameter("thin-lens", 0.0));
    QVERIFY(panel.setParameter("focus", 3.0));
    QVERIFY(panel.setParameter("blur", 0.02));
    QVERIFY(waitForGeneration(panel, panel.requestedGeneration()));
    const Artcam camera = buildEffect("depth-of-field", panel.parameters(), {64, 48});
    QVERIFY(camera.depth_output == DepthOutput::BlurVariance);
    for (const double d : {0.5, 3.0, 9.0}) {
      Eigen::VectorXd x(9);
      x << 0.0, 0.0, 1, 0.5, 0.5, 0.5, 1, d, 1;
      const double expected = 0.02 * 0.02 * (d - 3.0) * (d - 3.0) / 9.0;
      QVERIFY(std::abs(camera.main().evaluate(x)[7] - expected) < 1e-12);
    }
  }

  void depthEffectsUseTheStandInAndSayWhy() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    panel.setEffect("aerial-perspective");
    QVERIFY(waitForGeneration(panel, panel.requestedGeneration()));
    QVERIFY2(panel.status().contains("ramp"), qPrintable(panel.status()));
    // A badly set range is reported, not thrown across the event loop.
    QVERIFY(panel.setParameter("near", 50.0));
    QVERIFY(panel.setParameter("far", 10.0));
    QVERIFY(waitForGeneration(panel, panel.requestedGeneration()));
    QVERIFY2(panel.status().contains("cannot render"), qPrintable(panel.status()));
  }

  // The GUI thread never waits for a render: with every render blocked on a gate the test holds
  // shut, parameter changes and the throttle's request still return at once (a wait would last
  // until the render's own 30 s give-up), and once the gate opens the last change is shown.
  void neverWaitsForARender() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    panel.setEffect("colour-shift");
    auto gate = std::make_shared<QSemaphore>();
    auto started = std::make_shared<std::atomic<int>>(0);
    panel.renderWorker()->setRender(
        [gate, started](const EffectRequest& r, const std::function<bool()>& keep_going) {
          ++*started;
          QElapsedTimer waited;
          waited.start();
          while (!gate->tryAcquire(1, 5)) {
            if (!keep_going() || waited.elapsed() > 30000) return EffectResult{};
          }
          QImage image(4, 4, QImage::Format_RGBA8888);
          image.fill(QColor::fromRgbF(static_cast<float>(r.values.at("s-red")[0]), 0.0f, 0.0f));
          return EffectResult{image, QStringLiteral("s-red %1").arg(r.values.at("s-red")[0])};
        });
    QTRY_VERIFY_WITH_TIMEOUT(started->load() >= 1, 20000);  // the first render is stuck
    const int renders_before = started->load();
    qint64 slowest_ms = 0;
    QElapsedTimer clock;
    for (int i = 1; i <= 30; ++i) {
      clock.start();
      QVERIFY(panel.setParameter("s-red", 0.01 * i));
      if (i % 10 == 0) QTest::qWait(120);  // the throttle fires: a new request, no join
      slowest_ms = std::max(slowest_ms, clock.elapsed());
    }
    QVERIFY2(slowest_ms < 5000, qPrintable(QString("a setter took %1 ms").arg(slowest_ms)));
    // Newer requests cancelled the stuck renders and started their own.
    QTRY_VERIFY_WITH_TIMEOUT(started->load() > renders_before, 20000);
    QCOMPARE(panel.previewGeneration(), quint64{0});  // nothing shown while the gate is shut
    gate->release(1000);
    QVERIFY(waitForGeneration(panel, panel.requestedGeneration()));
    QCOMPARE(panel.status(), QStringLiteral("s-red 0.3"));
    QCOMPARE(panel.preview().pixelColor(1, 1).red(), QColor::fromRgbF(0.3f, 0.0f, 0.0f).red());
  }

  void paintedDepthReachesThePanelInTheStudio() {
    MainWindow window;
    window.document()->reset(test::syntheticPhoto());
    auto* panel = window.findChild<EffectsPanel*>();
    QVERIFY(panel);
    panel->setEffect("aerial-perspective");
    QVERIFY(waitForGeneration(*panel, panel->requestedGeneration()));
    QVERIFY2(panel->status().contains("ramp"), qPrintable(panel->status()));
    // Paint a plane: the panel now reads it instead of the stand-in ramp; undo brings it back.
    DepthModel* depth = window.document()->depth();
    DepthPlaneLayer layer = depth->makeLayer();
    layer.mask.fillPolygon({{0, 0}, {320, 0}, {320, 240}, {0, 240}});
    layer.anchors = {{{0.0, 0.0}, 2.0}, {{320.0, 0.0}, 20.0}, {{0.0, 240.0}, 2.0}};
    // The depth reaches the panel through the depth overlay's throttled raster; every new
    // raster schedules a render, so wait for the panel to settle on its newest one.
    window.document()->undoStack()->push(new AddDepthLayerCommand(depth, layer));
    QTRY_VERIFY_WITH_TIMEOUT(waitForGeneration(*panel, panel->requestedGeneration()) &&
                                 !panel->status().contains("ramp"),
                             20000);
    window.document()->undoStack()->undo();
    QTRY_VERIFY_WITH_TIMEOUT(waitForGeneration(*panel, panel->requestedGeneration()) &&
                                 panel->status().contains("ramp"),
                             20000);
  }
};

QTEST_MAIN(TestEffectsPanel)
#include "test_effects_panel.moc"
