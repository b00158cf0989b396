// SPDX-License-Identifier: Apache-2.0
// Editing where the result shows: over the Result view a source click is mapped back through the
// camera's inverse, a source drag follows the cursor mapped back through the camera as it was
// when the drag began, and a depth brush paints the photo pixels under the result's pixels,
// while the canvas keeps showing the result. The truth is a homography built here (its inverse
// is Eigen's 3×3 inverse, not the engine's solver) that six exact pairs make the fitted camera.
// A click whose preimage is off the photo adds nothing and says why.
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/depth_commands.h"
#include "ui/document.h"
#include "ui/preview_controller.h"
#include "ui/tools/depth_tool.h"
#include "ui/tools/depth_tool_settings.h"
#include "ui/tools/pair_tool.h"

#include <Eigen/LU>

#include <QSignalSpy>
#include <QtTest/QtTest>

#include "core/model/artcam.h"

#include <cmath>

using namespace artcam;
using namespace artcam::ui;

namespace {

constexpr int kW = 320, kH = 240;

// Target pixels from source pixels (column form, x̃' = H x̃): a shrink towards the top left with
// a mild perspective, so result points near the frame's corners have no photo pixel under them.
Eigen::Matrix3d truthHomography() {
  Eigen::Matrix3d h;
  h << 0.8, 0.05, 20.0,  //
      0.03, 0.85, 15.0,  //
      2e-4, 1e-4, 1.0;
  return h;
}

Eigen::Vector2d apply(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1.0);
  return q.head<2>() / q.z();
}

Eigen::Vector2d truthPreimage(const Eigen::Vector2d& target) {
  return apply(truthHomography().inverse(), target);
}

std::vector<Pair> homographyPairs() {
  std::vector<Pair> out;
  for (const auto& [x, y] : {std::pair{30.0, 25.0},
                             {290.0, 30.0},
                             {40.0, 215.0},
                             {285.0, 210.0},
                             {150.0, 60.0},
                             {110.0, 170.0}})
    out.push_back({{x, y}, apply(truthHomography(), {x, y}), true});
  return out;
}

Eigen::Vector2d imageAt(const Canvas& canvas, const QPoint& widget) {
  const QPointF p = canvas.view().imageFromWidget(QPointF(widget));
  return {p.x(), p.y()};
}

// A plane over the whole photo, near at the bottom and far at the top.
DepthPlaneLayer wholePhotoPlane(const DepthModel& depth) {
  DepthPlaneLayer layer = depth.makeLayer();
  const double w = depth.frame().width, h = depth.frame().height;
  layer.mask.fillPolygon({{0, 0}, {w, 0}, {w, h}, {0, h}});
  layer.anchors = {{{0.5, h - 0.5}, 1.5}, {{w - 0.5, h - 0.5}, 1.5}, {{w / 2, 0.5}, 40.0}};
  return layer;
}

QString text(const Eigen::Vector2d& p) { return QString("(%1, %2)").arg(p.x()).arg(p.y()); }

struct Rig {
  Document doc;
  PreviewController preview{&doc};
  Canvas canvas{&doc};
  DepthToolSettings settings;

  Rig() {
    canvas.setPreview(&preview);
    canvas.setTool(std::make_unique<PairTool>(&canvas, &doc));
    canvas.resize(800, 600);
    canvas.show();
    doc.reset(test::syntheticPhoto(kW, kH), homographyPairs(), ModelClass::Homography);
  }
};

}  // namespace

class TestEditOnResult : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void aSourceClickedOnTheResultIsTheCamerasPreimage() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    QVERIFY(rig.doc.fit().status.ok);
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);
    // A result point inside the photo's image, where a feature shows that came from H⁻¹(t).
    const QPoint at = test::widgetPoint(rig.canvas, {200.0, 140.0});
    const Eigen::Vector2d t = imageAt(rig.canvas, at);
    test::click(&rig.canvas, at);
    auto* tool = dynamic_cast<PairTool*>(rig.canvas.tool());
    QVERIFY2(tool->hasPendingSource(), "a source click on the result was refused");
    // Its target where the feature is seen: the same result point.
    test::click(&rig.canvas, at);
    QCOMPARE(rig.doc.pairs().size(), size_t{7});
    const Pair added = rig.doc.pairs().back();
    const Eigen::Vector2d truth = truthPreimage(t);
    QVERIFY2((added.source - truth).norm() < 1e-3,
             qPrintable("source " + text(added.source) + ", preimage " + text(truth)));
    QVERIFY((added.target - t).norm() < 1e-9);
    // Split, right of the divider, is the result too.
    rig.doc.undoStack()->undo();
    rig.canvas.setViewMode(CanvasViewMode::Split);
    rig.canvas.setSplit(0.2);
    QVERIFY(rig.canvas.dividerX() < at.x());
    test::click(&rig.canvas, at);
    test::click(&rig.canvas, at);
    QCOMPARE(rig.doc.pairs().size(), size_t{7});
    QVERIFY((rig.doc.pairs().back().source - truth).norm() < 1e-3);
  }

  void draggingASourceOnTheResultFollowsTheCursorMappedBack() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    const Pair before = rig.doc.pairs()[4];
    const QPoint from = test::widgetPoint(rig.canvas, before.source);
    const QPoint to = from + QPoint(40, 30);
    test::drag(&rig.canvas, from, to);
    QTRY_VERIFY(!rig.doc.fitPending());
    const Pair after = rig.doc.pairs()[4];
    // The camera the drag began under is H (the pairs refit while it moves): the source moves
    // by the difference of the press and release points mapped back through H.
    const Eigen::Vector2d expected = before.source + truthPreimage(imageAt(rig.canvas, to)) -
                                     truthPreimage(imageAt(rig.canvas, from));
    QVERIFY2((after.source - expected).norm() < 1e-3,
             qPrintable("source " + text(after.source) + ", expected " + text(expected)));
    QVERIFY(after.target == before.target);
    // One undo step for the whole drag.
    rig.doc.undoStack()->undo();
    QVERIFY(rig.doc.pairs()[4] == before);
  }

  void aDepthBrushOnTheResultPaintsThePhotoPixelsUnderIt() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    rig.settings.setRadius(3.0);
    rig.settings.setHardness(1.0);
    rig.canvas.setTool(
        std::make_unique<DepthTool>(&rig.canvas, &rig.doc, &rig.settings, DepthToolMode::Brush));
    // The result (and its effects) stays on screen while depth is painted.
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);
    const QPoint at = test::widgetPoint(rig.canvas, {214.0, 164.0});
    const Eigen::Vector2d t = imageAt(rig.canvas, at);
    const Eigen::Vector2d s = truthPreimage(t);
    QVERIFY((s - t).norm() > 20.0);  // far enough apart for the test to tell them apart
    QVERIFY(test::waitForNewestPreview(rig.preview));
    const QImage before = rig.canvas.grab().toImage();
    test::click(&rig.canvas, at);
    QCOMPARE(rig.doc.depth()->layerCount(), 1);
    const RegionMask& mask = rig.doc.depth()->layer(0).mask;
    QCOMPARE(mask.at(static_cast<int>(s.x()), static_cast<int>(s.y())), uint8_t{255});
    QCOMPARE(mask.at(static_cast<int>(t.x()), static_cast<int>(t.y())), uint8_t{0});
    // The mask's tint lies where the result shows the painted pixels (under the cursor), not
    // where they are in the photo.
    const QImage after = rig.canvas.grab().toImage();
    const QPoint on_photo = test::widgetPoint(rig.canvas, s);
    QVERIFY(after.pixel(at) != before.pixel(at));
    QCOMPARE(after.pixel(on_photo), before.pixel(on_photo));
    // A stroke: every dab lands on the preimage of the cursor's result point.
    const QPoint end = at + QPoint(0, 60);
    test::drag(&rig.canvas, at, end);
    for (int k = 0; k <= 6; ++k) {
      const Eigen::Vector2d p = truthPreimage(imageAt(rig.canvas, at + (end - at) * k / 6));
      QCOMPARE(mask.at(static_cast<int>(p.x()), static_cast<int>(p.y())), uint8_t{255});
    }
  }

  // Depth of field reads the depth, and stays on screen while another plane is painted on the
  // result through the same inverse (its blur moves no pixel).
  void aPlaneIsPaintedOnTheResultWhileDepthOfFieldShows() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    rig.doc.undoStack()->push(
        new AddDepthLayerCommand(rig.doc.depth(), wholePhotoPlane(*rig.doc.depth())));
    rig.doc.setEffects({EffectStep{"depth-of-field", {}}});
    QVERIFY2(readsDepth(rig.doc.artcam()), rig.doc.artcamNote().c_str());
    rig.doc.undoStack()->push(
        new AddDepthLayerCommand(rig.doc.depth(), rig.doc.depth()->makeLayer()));
    const int painted = rig.doc.depth()->activeLayer();
    QVERIFY(painted >= 0 && rig.doc.depth()->layerCount() == 2);
    rig.settings.setRadius(3.0);
    rig.settings.setHardness(1.0);
    rig.canvas.setTool(
        std::make_unique<DepthTool>(&rig.canvas, &rig.doc, &rig.settings, DepthToolMode::Brush));
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);
    const QPoint at = test::widgetPoint(rig.canvas, {214.0, 164.0});
    const Eigen::Vector2d s = truthPreimage(imageAt(rig.canvas, at));
    test::click(&rig.canvas, at);
    const RegionMask& mask = rig.doc.depth()->layer(painted).mask;
    QCOMPARE(mask.at(static_cast<int>(s.x()), static_cast<int>(s.y())), uint8_t{255});
    QVERIFY(readsDepth(rig.doc.artcam()));
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);
  }

  // A camera whose positions read depth (a pushbroom of the depth planes, eq 8/9) has no point
  // inverse: a source click on its result is refused and says to work on the photo.
  void aCameraWhosePositionsReadDepthRefusesWithAMessage() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    rig.doc.undoStack()->push(
        new AddDepthLayerCommand(rig.doc.depth(), wholePhotoPlane(*rig.doc.depth())));
    rig.doc.setEffects({EffectStep{"photo-pushbroom", {}}});
    QVERIFY2(readsDepth(rig.doc.artcam()), rig.doc.artcamNote().c_str());
    QSignalSpy messages(&rig.canvas, &Canvas::toolMessage);
    test::click(&rig.canvas, test::widgetPoint(rig.canvas, {160.0, 120.0}));
    QVERIFY(!dynamic_cast<PairTool*>(rig.canvas.tool())->hasPendingSource());
    QVERIFY(messages.count() >= 1);
    const QString said = messages.last().at(0).toString();
    QVERIFY2(said.contains("\\") && said.contains("photo"), qPrintable(said));
    // On the photo the same click places the source.
    rig.canvas.setViewMode(CanvasViewMode::Photo);
    test::click(&rig.canvas, test::widgetPoint(rig.canvas, {160.0, 120.0}));
    QVERIFY(dynamic_cast<PairTool*>(rig.canvas.tool())->hasPendingSource());
  }

  void aClickWithNoPreimageIsRefusedWithAMessage() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    QSignalSpy messages(&rig.canvas, &Canvas::toolMessage);
    // The result's top-left corner: H⁻¹ puts it left of and above the photo.
    const Eigen::Vector2d corner(4.0, 4.0);
    QVERIFY(truthPreimage(corner).x() < 0.0 && truthPreimage(corner).y() < 0.0);
    const QPoint at = test::widgetPoint(rig.canvas, corner);
    test::click(&rig.canvas, at);
    auto* tool = dynamic_cast<PairTool*>(rig.canvas.tool());
    QVERIFY(!tool->hasPendingSource());
    QVERIFY(messages.count() >= 1);
    const QString said = messages.last().at(0).toString();
    QVERIFY2(said.contains("photo", Qt::CaseInsensitive), qPrintable(said));
    test::click(&rig.canvas, test::widgetPoint(rig.canvas, {160.0, 120.0}));
    QCOMPARE(rig.doc.pairs().size(), size_t{6});  // the second click was a source, not a pair
    // The depth brush refuses the same point the same way and paints nothing.
    rig.canvas.setTool(
        std::make_unique<DepthTool>(&rig.canvas, &rig.doc, &rig.settings, DepthToolMode::Brush));
    const int before = static_cast<int>(messages.count());
    test::click(&rig.canvas, at);
    QVERIFY(messages.count() > before);
    QVERIFY(rig.doc.depth()->layerCount() == 0 || rig.doc.depth()->layer(0).mask.empty() ||
            std::all_of(rig.doc.depth()->layer(0).mask.coverage().begin(),
                        rig.doc.depth()->layer(0).mask.coverage().end(),
                        [](uint8_t v) { return v == 0; }));
  }
};

QTEST_MAIN(TestEditOnResult)
#include "test_edit_on_result.moc"
