// SPDX-License-Identifier: Apache-2.0
// The effects panel edits the document's effect stack: every edit is one undo step (a run of
// edits of one parameter merges), an effect that reads depth joins the camera once the document
// has depth and leaves it again on undo, and the main preview shows the stack.
#include "core/effects/effect_table.h"
#include "core/pipeline/render.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/depth_commands.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/image_convert.h"
#include "ui/main_window.h"
#include "ui/panels/effects_panel.h"
#include "ui/preview_controller.h"
#include "ui/render_worker.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;
using namespace artcam::ui;

namespace {

DepthPlaneLayer wholePhotoPlane(const DepthModel& depth, double near, double far) {
  DepthPlaneLayer layer = depth.makeLayer();
  const double w = depth.frame().width, h = depth.frame().height;
  layer.mask.fillPolygon({{0, 0}, {w, 0}, {w, h}, {0, h}});
  layer.anchors = {{{0.5, h - 0.5}, near}, {{w - 0.5, h - 0.5}, near}, {{w / 2, 0.5}, far}};
  return layer;
}

}  // namespace

class TestEffectsPanel : public QObject {
  Q_OBJECT

 private slots:
  void stackEditsAreUndoable() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    QVERIFY(!panel.addEffect("no-such-effect"));
    QVERIFY(panel.addEffect("barrel"));
    QVERIFY(panel.addEffect("twist"));
    QCOMPARE(doc.effects().size(), size_t{2});
    QCOMPARE(panel.selectedIndex(), 1);
    // Three edits of one parameter in a row are one undo step.
    QVERIFY(panel.setParameter("rate", 0.1));
    QVERIFY(panel.setParameter("rate", 0.2));
    QVERIFY(panel.setParameter("rate", 0.25));
    QCOMPARE(doc.effects()[1].values.at("rate"), std::vector<double>{0.25});
    QVERIFY(!panel.setParameter("k", 0.1));  // barrel's parameter: not the selected entry's
    panel.moveSelected(-1);
    QCOMPARE(doc.effects()[0].effect, std::string("twist"));
    QCOMPARE(panel.selectedIndex(), 0);
    panel.removeSelected();
    QCOMPARE(doc.effects().size(), size_t{1});
    QCOMPARE(doc.effects()[0].effect, std::string("barrel"));
    QUndoStack* stack = doc.undoStack();
    QCOMPARE(stack->count(), 5);  // add, add, set rate, move, remove
    stack->undo();                // remove
    stack->undo();                // move
    QCOMPARE(doc.effects()[1].effect, std::string("twist"));
    stack->undo();  // the three rate edits at once
    QCOMPARE(doc.effects()[1].values.at("rate"), std::vector<double>{0.3});  // the default
    // The panel's spin box follows the undo.
    panel.setSelectedIndex(1);
    QCOMPARE(panel.parameters().at("rate"), std::vector<double>{0.3});
    stack->undo();
    stack->undo();
    QVERIFY(doc.effects().empty());
    // The stack is part of the whole camera: barrel then twist is two stages after the
    // identity geometry's, and undoing it leaves the geometry alone.
    QCOMPARE(doc.artcam().kind(), ArtcamKind::Single);
    stack->redo();
    QVERIFY(doc.artcam().main().stages().size() >= 1);
    const Eigen::Vector3d corner(-0.9, -0.55, 1.0);  // near the frame's corner (normalised)
    const Eigen::VectorXd moved = doc.artcam().main().evaluate(corner);
    QVERIFY2((moved.head<2>() - corner.head<2>()).norm() > 0.01, "barrel moved nothing");
  }

  void depthEffectsWaitForDepth() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    EffectsPanel panel(&doc);
    QVERIFY(panel.addEffect("aerial-perspective"));
    QVERIFY(!readsDepth(doc.artcam()));
    QVERIFY2(panel.status().contains("reads depth"), qPrintable(panel.status()));
    // A painted plane with its three depths: the effect joins the camera.
    doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), wholePhotoPlane(*doc.depth(), 1, 50)));
    QVERIFY(readsDepth(doc.artcam()));
    QVERIFY2(doc.artcamNote().empty(), doc.artcamNote().c_str());
    QVERIFY2(panel.status().contains("applied"), qPrintable(panel.status()));
    doc.undoStack()->undo();
    QVERIFY(!readsDepth(doc.artcam()));
  }

  // The multi-perspective effects (core/effects/multi_perspective.h) need nothing beyond their
  // table rows: each waits for depth, then joins the document's camera, which renders with the
  // document's depth raster through the splat exactly as the row's own camera does (rendered
  // directly: the independent path), and visibly differs from the photo.
  void multiPerspectiveEffectsRenderWithDepth() {
    for (const char* name : {"photo-pushbroom", "photo-xslit", "photo-glc"}) {
      Document doc;
      doc.reset(test::syntheticPhoto(160, 120));
      EffectsPanel panel(&doc);
      QVERIFY2(panel.addEffect(name), name);
      QVERIFY2(!readsDepth(doc.artcam()), name);
      QVERIFY2(panel.status().contains("reads depth"), qPrintable(panel.status()));
      doc.undoStack()->push(
          new AddDepthLayerCommand(doc.depth(), wholePhotoPlane(*doc.depth(), 2, 8)));
      QVERIFY2(readsDepth(doc.artcam()), name);
      QVERIFY2(doc.artcamNote().empty(), doc.artcamNote().c_str());
      const ImageF depth = doc.depth()->rasterise();
      const ImageF& photo = doc.photo()->full.image;
      RenderSummary summary;
      const ImageF got = render(RenderInputs::of(photo, &depth), doc.artcam(), {}, &summary);
      QCOMPARE(summary.path, RenderPath::Splat);
      const ImageF want =
          render(RenderInputs::of(photo, &depth), buildEffect(name, {}, doc.frame()));
      QCOMPARE(got.width, want.width);
      QCOMPARE(got.height, want.height);
      QCOMPARE(got.channels, 4);
      double off = 0.0, changed = 0.0, covered = 0.0;
      for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x) {
          for (int c = 0; c < 4; ++c) off += std::abs(got.pixel(x, y)[c] - want.pixel(x, y)[c]);
          for (int c = 0; c < 3; ++c) changed += std::abs(got.pixel(x, y)[c] - photo.pixel(x, y)[c]);
          covered += got.pixel(x, y)[3];
        }
      const double n = static_cast<double>(got.width) * got.height;
      QVERIFY2(off / (4 * n) < 1e-4, qPrintable(QString("%1 off by %2").arg(name).arg(off / (4 * n))));
      QVERIFY2(changed / (3 * n) > 0.01, qPrintable(QString("%1 invisible: %2").arg(name).arg(changed / (3 * n))));
      QVERIFY2(covered / n > 0.5, qPrintable(QString("%1 mostly transparent: %2").arg(name).arg(covered / n)));
    }
  }

  void previewShowsTheStack() {
    MainWindow window;
    window.document()->reset(test::syntheticPhoto(640, 480));
    PreviewController* preview = window.preview();
    QVERIFY(test::waitForNewestPreview(*preview));
    const QImage before = preview->image();
    auto* panel = window.findChild<EffectsPanel*>();
    QVERIFY(panel);
    QVERIFY(panel->addEffect("barrel"));
    QVERIFY(test::waitForNewestPreview(*preview));
    const QImage after = preview->image();
    // The independent truth: the barrel effect's own camera from the table, rendered directly
    // on the preview copy at the preview's size.
    const PhotoPtr& photo = window.document()->photo();
    const Artcam barrel = buildEffect("barrel", {}, window.document()->frame());
    RenderOptions options;
    options.warp = RenderWorker::passOptions(after.width(), after.height());
    const QImage want = qimageFromLinear(render(RenderInputs::of(photo->preview), barrel, options));
    QCOMPARE(after.size(), want.size());
    const double off = test::meanDifference(after, want);
    const double unchanged = test::meanDifference(before, want);
    // The preview samples the photo's 8-bit pyramid, the direct render the float preview copy.
    QVERIFY2(off < 2.5, qPrintable(QString("preview differs from the effect by %1").arg(off)));
    QVERIFY2(unchanged > 4 * off + 1.0, qPrintable(QString("the effect is invisible: %1").arg(unchanged)));
  }
};

QTEST_MAIN(TestEffectsPanel)
#include "test_effects_panel.moc"
