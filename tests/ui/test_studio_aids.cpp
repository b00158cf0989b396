// SPDX-License-Identifier: Apache-2.0
// The studio's visible state and aids: the active tool shown in the toolbar, the cursor and
// the status bar, and reset to the pair tool by a new photo.
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/canvas_annotations.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/help_dialogs.h"
#include "ui/main_window.h"
#include "ui/manual_camera_banner.h"
#include "ui/matting/insertion_studio.h"
#include "ui/panels/pairs_panel.h"
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
#include <QRegularExpression>
#include <QStandardPaths>
#include <QTableView>
#include <QTableWidget>
#include <QToolBar>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

namespace {

QImage cursorImage(const QWidget& w) { return w.cursor().pixmap().toImage(); }

// A flat photo of one grey level.
PhotoPtr flatPhoto(int w, int h, float level) {
  ImageF img(w, h, 3);
  for (float& v : img.data) v = level;
  LoadedImage loaded;
  loaded.image = std::move(img);
  return makePhoto(QStringLiteral("flat.png"), std::move(loaded));
}

bool near(const QColor& a, const QColor& b, int tolerance) {
  return std::abs(a.red() - b.red()) <= tolerance && std::abs(a.green() - b.green()) <= tolerance &&
         std::abs(a.blue() - b.blue()) <= tolerance;
}

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
        new SetCameraCommand(doc, Artcam(identityImageCamera(doc->frame())), QStringLiteral("Edit")));
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

  void gridOverlayDrawsThirdsOverThePicture() {
    Document doc;
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    doc.reset(flatPhoto(300, 200, 0.5f));
    const QImage off = canvas.grab().toImage();
    canvas.setGridVisible(true);
    const QImage on = canvas.grab().toImage();
    // The picture's rectangle, computed from the view; the thirds at 1/3 and 2/3 of it.
    const QRectF r = canvas.view().widgetFromImage(QRectF(0, 0, 300, 200));
    const int x_third = static_cast<int>(std::floor(r.left() + r.width() / 3));
    const int y_mid_cell = static_cast<int>(r.top() + r.height() / 16);  // half an eighth down
    const int y_third = static_cast<int>(std::floor(r.top() + 2 * r.height() / 3));
    const int x_mid_cell = static_cast<int>(r.left() + r.width() / 16);
    QVERIFY(on.pixelColor(x_third, y_mid_cell) != off.pixelColor(x_third, y_mid_cell));
    QVERIFY(on.pixelColor(x_mid_cell, y_third) != off.pixelColor(x_mid_cell, y_third));
    // Inside a cell, away from every line, the picture is unchanged; outside it too.
    QCOMPARE(on.pixelColor(x_mid_cell, y_mid_cell), off.pixelColor(x_mid_cell, y_mid_cell));
    QCOMPARE(on.pixelColor(2, 2), off.pixelColor(2, 2));
  }

  void residualLegendAndMagnifiedVectors() {
    Document doc;
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    // A translation fitted to two pairs moved by 10 and 14 px: t = 12 px (least squares), so
    // the residual vectors, clicked − fitted target, are (−2, 0) and (+2, 0).
    Pair a, b;
    a.source = {100, 100};
    a.target = {110, 100};
    b.source = {200, 160};
    b.target = {214, 160};
    doc.reset(flatPhoto(320, 240, 0.2f), {a, b}, ModelClass::Translation);
    QVERIFY(std::abs(doc.residual(0) - 2.0) < 1e-6);
    const QImage plain = canvas.grab().toImage();
    // The legend: green at its left end, red at its right (the marker ramp's ends by hand:
    // (0, 220, 40) at 0 px and (255, 0, 40) at ≥ 4 px).
    const QRectF bar = residualLegendBar(canvas.size());
    const int cy = static_cast<int>(bar.center().y());
    QVERIFY(near(plain.pixelColor(static_cast<int>(bar.left()) + 1, cy), QColor(0, 220, 40), 16));
    QVERIFY(near(plain.pixelColor(static_cast<int>(bar.right()) - 2, cy), QColor(255, 0, 40), 16));
    // Magnified ×10: pair 1's vector runs from its fitted target (112, 100) to 112 − 20 = 92.
    canvas.setResidualsMagnified(true);
    const QImage magnified = canvas.grab().toImage();
    const QPoint on_vector = ui::test::widgetPoint(canvas, {95, 100});
    const QPoint beyond = ui::test::widgetPoint(canvas, {88, 100});
    QVERIFY(plain.pixelColor(on_vector) == plain.pixelColor(beyond));  // empty photo there
    const QColor v = magnified.pixelColor(on_vector);
    QVERIFY2(near(v, Canvas::residualColour(2.0), 40), qPrintable(v.name()));
    QCOMPARE(magnified.pixelColor(beyond), plain.pixelColor(beyond));
    // No pairs, no legend.
    doc.reset(flatPhoto(320, 240, 0.2f));
    const QImage empty = canvas.grab().toImage();
    QCOMPARE(empty.pixelColor(static_cast<int>(bar.right()) - 2, cy),
             empty.pixelColor(static_cast<int>(bar.right()) - 2, cy - 40));
  }

  void pairLabelsHaveAHalo() {
    Document doc;
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    Pair p;
    p.source = {160, 120};
    p.target = {140, 140};  // down-left: the arrow stays away from the label
    doc.reset(flatPhoto(320, 240, 1.0f), {p}, ModelClass::Translation);
    const QImage img = canvas.grab().toImage();
    // White text on a white photo shows only through its dark halo.
    const QPointF s = canvas.view().widgetFromImage(QPointF(160, 120));
    int dark = 0;
    for (int y = static_cast<int>(s.y()) - 20; y < static_cast<int>(s.y()) - 8; ++y)
      for (int x = static_cast<int>(s.x()) + 7; x < static_cast<int>(s.x()) + 20; ++x)
        dark += img.pixelColor(x, y).lightness() < 80;
    QVERIFY2(dark >= 10, qPrintable(QString::number(dark)));
  }

  void shortcutTableListsEveryShortcut() {
    MainWindow window;
    auto* extra = new QAction(QStringLiteral("&Late Action"), &window);
    extra->setShortcut(QKeySequence(QStringLiteral("Ctrl+Alt+J")));
    std::unique_ptr<QTableWidget> table(makeShortcutTable(&window));
    QMultiMap<QString, QString> rows;  // action text → its shortcuts cell
    for (int r = 0; r < table->rowCount(); ++r)
      rows.insert(table->item(r, 0)->text(), table->item(r, 1)->text());
    int with_shortcut = 0;
    for (const QAction* a : window.findChildren<QAction*>()) {
      if (a->shortcuts().isEmpty()) continue;
      ++with_shortcut;
      const QString text = a->text().remove(QRegularExpression(QStringLiteral("&(?!&)")));
      QVERIFY2(rows.contains(text), qPrintable(text));
      for (const QKeySequence& k : a->shortcuts()) {
        const QString key = k.toString(QKeySequence::NativeText);
        bool found = false;
        for (const QString& cell : rows.values(text)) found = found || cell.contains(key);
        QVERIFY2(found, qPrintable(text + ": " + key));
      }
    }
    QCOMPARE(table->rowCount(), with_shortcut);
    QVERIFY(rows.contains(QStringLiteral("Late Action")));
    // The ones this part added, by hand.
    QVERIFY(rows.value(QStringLiteral("Redo")).contains(QStringLiteral("Ctrl+Y")));
    QVERIFY(rows.value(QStringLiteral("Show Grid")).contains(QStringLiteral("Ctrl+'")));
    QVERIFY(rows.contains(QStringLiteral("Keyboard Shortcuts")));
    QVERIFY(rows.contains(QStringLiteral("Quick Start")));
    QVERIFY(quickStartHtml().contains(QStringLiteral("Open a photo")));
  }

  void ctrlYRedoesAndSpacePansOverTheCanvas() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    Document* doc = window.document();
    doc->reset(ui::test::syntheticPhoto());
    for (const Pair& p : ui::test::ninePairs()) doc->undoStack()->push(new AddPairCommand(doc, p));
    doc->undoStack()->undo();
    QCOMPARE(doc->pairs().size(), size_t{8});
    window.canvas()->setFocus();
    QTest::keyClick(&window, Qt::Key_Y, Qt::ControlModifier);
    QCOMPARE(doc->pairs().size(), size_t{9});

    // The pairs table has the focus, on the first pair's cells; the pointer is over the canvas.
    Canvas* canvas = window.canvas();
    QTableView* table = window.pairsPanel()->table();
    table->setFocus();
    table->setCurrentIndex(table->model()->index(0, 0));
    const QPoint at(canvas->width() / 2, canvas->height() / 2);
    ui::test::sendMouse(canvas, QEvent::MouseMove, at, Qt::NoButton, Qt::NoButton);
    QTest::keyPress(table, Qt::Key_Space);
    QVERIFY(canvas->isSpacePanning());
    const QPointF before = canvas->view().widgetFromImage(QPointF(100, 100));
    ui::test::drag(canvas, at, at + QPoint(40, -25));
    const QPointF after = canvas->view().widgetFromImage(QPointF(100, 100));
    QCOMPARE(after - before, QPointF(40, -25));
    QTest::keyRelease(table, Qt::Key_Space);
    QVERIFY(!canvas->isSpacePanning());
    for (const Pair& p : doc->pairs()) QVERIFY(p.enabled);  // the table did not toggle one
    QCOMPARE(doc->pairs().size(), size_t{9});               // and the drag made no pair

    // Pointer elsewhere: Space is the table's again.
    QEvent leave(QEvent::Leave);
    QCoreApplication::sendEvent(canvas, &leave);
    QTest::keyPress(table, Qt::Key_Space);
    QVERIFY(!canvas->isSpacePanning());
    QTest::keyRelease(table, Qt::Key_Space);
  }

  void reopeningAProjectFitsTheView() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto());
    ViewState saved;
    saved.scale = 7.5;
    saved.centre = QPointF(20, 30);
    emit window.session()->viewStateLoaded(saved);
    ViewTransform fitted;
    fitted.fit(QSizeF(window.canvas()->size()), QSizeF(320, 240));
    QCOMPARE(window.canvas()->view().scale(), fitted.scale());
    QCOMPARE(window.canvas()->view().widgetFromImage(QPointF(160, 120)),
             fitted.widgetFromImage(QPointF(160, 120)));
  }
};

QTEST_MAIN(TestStudioAids)
#include "test_studio_aids.moc"
