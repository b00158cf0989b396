// SPDX-License-Identifier: Apache-2.0
// The studio's visible state and aids: the active tool shown in the toolbar, the cursor and
// the status bar, and reset to the pair tool by a new photo.
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/main_window.h"
#include "ui/manual_camera_banner.h"
#include "ui/matting/insertion_studio.h"
#include "ui/session.h"
#include "ui/tool_switcher.h"
#include "ui/tools/depth_tool.h"
#include "ui/tools/depth_tool_settings.h"
#include "ui/tools/grid_tool.h"
#include "ui/tools/pair_tool.h"
#include "ui/tools/region_tool.h"

#include <QAction>
#include <QActionGroup>
#include <QLabel>
#include <QPushButton>
#include <QStandardPaths>
#include <QToolBar>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

namespace {

QImage cursorImage(const QWidget& w) { return w.cursor().pixmap().toImage(); }

// A photo of two flat colours meeting at x = edge (photo pixels): dark left, light right.
PhotoPtr twoTonePhoto(int w, int h, int edge) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = x < edge ? 0.05f : 0.8f;
  LoadedImage loaded;
  loaded.image = std::move(img);
  return makePhoto(QStringLiteral("two_tone.png"), std::move(loaded));
}

}  // namespace

class TestStudioAids : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void activeToolIsShownAndResetByANewPhoto() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto());
    auto* studio = window.findChild<InsertionStudio*>();
    QVERIFY(studio);
    ToolSwitcher* tools = window.toolSwitcher();
    QAction* pairs = tools->defaultAction();
    QVERIFY(pairs && pairs->isChecked());
    QVERIFY(dynamic_cast<PairTool*>(window.canvas()->tool()));
    QCOMPARE(tools->label()->text(), QStringLiteral("Tool: Pairs"));
    const QImage pair_cursor = cursorImage(*window.canvas());
    QVERIFY(!pair_cursor.isNull());

    // The Insertion tools are in the toolbar and in the same exclusive group.
    auto* bar = window.findChild<QToolBar*>(QStringLiteral("mainToolBar"));
    QVERIFY(bar);
    QVERIFY(bar->actions().contains(studio->gridToolAction()));
    QVERIFY(bar->actions().contains(studio->regionToolAction()));
    QVERIFY(bar->actions().contains(pairs));
    studio->regionToolAction()->trigger();
    QVERIFY(dynamic_cast<RegionTool*>(window.canvas()->tool()));
    QVERIFY(studio->regionToolAction()->isChecked());
    QVERIFY(!pairs->isChecked());
    QCOMPARE(tools->group()->checkedAction(), studio->regionToolAction());
    QVERIFY(tools->label()->text().contains("region"));
    const QImage region_cursor = cursorImage(*window.canvas());
    QVERIFY(region_cursor != pair_cursor);

    // A depth tool unchecks the Insertion tool; each tool has its own cursor.
    window.canvas()->setFocus();
    QTest::keyClick(&window, Qt::Key_B);
    QVERIFY(dynamic_cast<DepthTool*>(window.canvas()->tool()));
    QVERIFY(!studio->regionToolAction()->isChecked());
    QCOMPARE(tools->label()->text(), QStringLiteral("Tool: Depth brush"));
    const QImage brush_cursor = cursorImage(*window.canvas());
    QVERIFY(brush_cursor != pair_cursor && brush_cursor != region_cursor);

    // Space shows the pan hand; releasing it brings the tool's cursor back, not an arrow.
    window.canvas()->setSpacePan(true);
    QCOMPARE(window.canvas()->cursor().shape(), Qt::OpenHandCursor);
    window.canvas()->setSpacePan(false);
    QCOMPARE(cursorImage(*window.canvas()), brush_cursor);

    // A new photo: back to the pair tool, so the first clicks make pairs.
    studio->gridToolAction()->trigger();
    QVERIFY(dynamic_cast<GridTool*>(window.canvas()->tool()));
    window.document()->reset(ui::test::syntheticPhoto(200, 150));
    QVERIFY(dynamic_cast<PairTool*>(window.canvas()->tool()));
    QVERIFY(pairs->isChecked());
    QVERIFY(!studio->gridToolAction()->isChecked());
    QCOMPARE(tools->label()->text(), QStringLiteral("Tool: Pairs"));
    const Canvas& canvas = *window.canvas();
    ui::test::click(window.canvas(), ui::test::widgetPoint(canvas, {50, 50}));
    QVERIFY(static_cast<PairTool*>(window.canvas()->tool())->hasPendingSource());
  }

  void depthStrokeShowsAtOnceAndStopsAtEdges() {
    Document doc;
    DepthToolSettings settings;
    settings.setRadius(12.0);
    settings.setHardness(1.0);
    settings.setEdgeAware(true);
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    doc.reset(twoTonePhoto(100, 60, 50));
    canvas.setTool(std::make_unique<DepthTool>(&canvas, &doc, &settings, DepthToolMode::Brush));
    const QImage before = canvas.grab().toImage();
    // A stroke down the dark side, its disc reaching 7 px over the edge.
    ui::test::drag(&canvas, ui::test::widgetPoint(canvas, {45.5, 40.5}),
                   ui::test::widgetPoint(canvas, {45.5, 20.5}));
    QCOMPARE(doc.depth()->layerCount(), 1);
    const RegionMask& mask = doc.depth()->layer(0).mask;
    QCOMPARE(mask.at(45, 30), uint8_t{255});
    QCOMPARE(mask.at(40, 30), uint8_t{255});
    for (int y = 0; y < 60; ++y)
      for (int x = 50; x < 100; ++x) QCOMPARE(mask.at(x, y), uint8_t{0});
    // Not a plane yet (no depth points), yet the painted pixels are tinted on the canvas.
    QVERIFY(!doc.depth()->plane(0));
    ui::test::sendMouse(&canvas, QEvent::MouseMove, QPoint(5, 5), Qt::NoButton, Qt::NoButton);
    const QImage after = canvas.grab().toImage();
    const QPoint painted = ui::test::widgetPoint(canvas, {40.5, 30.5});
    const QPoint other_side = ui::test::widgetPoint(canvas, {56.5, 30.5});
    const QColor b = before.pixelColor(painted), a = after.pixelColor(painted);
    QVERIFY2(a.blue() > b.blue() + 40 && a.green() > b.green() + 40,
             qPrintable(QString("%1 -> %2").arg(b.name(), a.name())));
    QCOMPARE(after.pixelColor(other_side), before.pixelColor(other_side));
  }

  void handSetCameraShowsABannerAndNeutralMarkers() {
    MainWindow window;
    window.session()->setInteractive(false);
    // No photo: the status bar names no model (nothing is fitted).
    QVERIFY(window.fitStatus()->modelText().isEmpty());
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    Document* doc = window.document();
    doc->reset(ui::test::syntheticPhoto());
    for (const Pair& p : ui::test::ninePairs()) doc->undoStack()->push(new AddPairCommand(doc, p));
    auto* banner = window.findChild<ManualCameraBanner*>();
    QVERIFY(banner);
    QVERIFY(!banner->isVisibleTo(window.canvas()));
    Canvas* canvas = window.canvas();
    const QPoint target = ui::test::widgetPoint(*canvas, doc->pairs()[4].target);
    QVERIFY(canvas->grab().toImage().pixelColor(target) != Canvas::kUnfittedPairColour);

    // The identity set by hand: every pair is several pixels off it.
    doc->undoStack()->push(
        new SetCameraCommand(doc, identityImageCamera(doc->frame()), QStringLiteral("Edit")));
    QVERIFY(doc->residual(4) > Canvas::kRedResidualPx);
    QVERIFY(banner->isVisibleTo(canvas));
    QVERIFY(banner->text().contains("Camera set by hand"));
    QCOMPARE(banner->y(), 0);
    QCOMPARE(banner->width(), canvas->width());
    QCOMPARE(canvas->grab().toImage().pixelColor(target), Canvas::kUnfittedPairColour);
    QVERIFY(window.fitStatus()->residualText().contains("not fitted"));

    // Fit again: one undo step back to the fit.
    banner->fitAgainButton()->click();
    QVERIFY(!doc->manualCamera());
    QVERIFY(!banner->isVisibleTo(canvas));
    QVERIFY(doc->residual(4) < 1.0);
    doc->undoStack()->undo();
    QVERIFY(doc->manualCamera());
    QVERIFY(banner->isVisibleTo(canvas));
  }
};

QTEST_MAIN(TestStudioAids)
#include "test_studio_aids.moc"
