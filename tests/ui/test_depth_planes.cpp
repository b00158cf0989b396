// SPDX-License-Identifier: Apache-2.0
// Depth planes in the studio: brush, eraser and polygon strokes on the canvas become one undo
// step each and undo restores the mask exactly; three clicked depth points give the plane
// (checked against the affine interpolation of their inverse depths, computed here); typed
// depths; the overlay and its legend range; depth in the project file (v2, v1 still read);
// depth map files loaded off the GUI thread as an undoable edit.
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/depth_commands.h"
#include "ui/depth_overlay.h"
#include "ui/document.h"
#include "ui/panels/depth_panel.h"
#include "ui/project_file.h"
#include "ui/session.h"
#include "ui/tools/depth_tool.h"
#include "ui/tools/depth_tool_settings.h"

#include <QDoubleSpinBox>
#include <QFile>
#include <QLabel>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

struct Rig {
  Document doc;
  DepthToolSettings settings;
  Canvas canvas{&doc};

  explicit Rig(DepthToolMode mode) {
    canvas.resize(640, 480);
    doc.reset(test::syntheticPhoto());
    canvas.zoomToFit();
    use(mode);
  }
  void use(DepthToolMode mode) {
    canvas.setTool(std::make_unique<DepthTool>(&canvas, &doc, &settings, mode));
  }
  QPoint at(double x, double y) const { return test::widgetPoint(canvas, {x, y}); }
  Eigen::Vector2d image(const QPoint& p) const {
    const QPointF q = canvas.view().imageFromWidget(QPointF(p));
    return {q.x(), q.y()};
  }
  const RegionMask& mask(int i = 0) const { return doc.depth()->layer(i).mask; }
};

// 1/z at p by affine interpolation of the anchors' inverse depths (barycentric coordinates):
// the plane through three points, computed without the solver under test.
double interpolatedInverseDepth(const std::vector<DepthAnchor>& a, const Eigen::Vector2d& p) {
  const Eigen::Vector2d v0 = a[1].pixel - a[0].pixel, v1 = a[2].pixel - a[0].pixel,
                        v2 = p - a[0].pixel;
  const double d = v0.x() * v1.y() - v1.x() * v0.y();
  const double l1 = (v2.x() * v1.y() - v1.x() * v2.y()) / d;
  const double l2 = (v0.x() * v2.y() - v2.x() * v0.y()) / d;
  return (1.0 - l1 - l2) / a[0].depth + l1 / a[1].depth + l2 / a[2].depth;
}

}  // namespace

class TestDepthPlanes : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
  }

  void brushStrokeIsOneUndoStep() {
    Rig rig(DepthToolMode::Brush);
    rig.settings.setRadius(6.0);
    rig.settings.setHardness(1.0);
    QCOMPARE(rig.doc.depth()->layerCount(), 0);
    test::drag(&rig.canvas, rig.at(40, 60), rig.at(200, 60), 12);
    // The first stroke made the layer: both are one undo step.
    QCOMPARE(rig.doc.depth()->layerCount(), 1);
    QCOMPARE(rig.doc.undoStack()->count(), 1);
    QVERIFY(rig.doc.isModified());
    const Eigen::Vector2d from = rig.image(rig.at(40, 60)), to = rig.image(rig.at(200, 60));
    for (double x = from.x(); x <= to.x(); x += 3.0)
      QCOMPARE(rig.mask().at(static_cast<int>(x), static_cast<int>(from.y())), uint8_t{255});
    QCOMPARE(rig.mask().at(120, 100), uint8_t{0});
    QCOMPARE(rig.mask().at(20, 60), uint8_t{0});
    const RegionMask painted = rig.mask();

    // A second stroke (erasing across) is a second step; undo gives back the first exactly.
    rig.use(DepthToolMode::Eraser);
    test::drag(&rig.canvas, rig.at(120, 30), rig.at(120, 90));
    QCOMPARE(rig.doc.undoStack()->count(), 2);
    QCOMPARE(rig.mask().at(120, 60), uint8_t{0});
    rig.doc.undoStack()->undo();
    QVERIFY(rig.mask() == painted);
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.doc.depth()->layerCount(), 0);
    rig.doc.undoStack()->redo();
    QVERIFY(rig.mask() == painted);
  }

  void polygonFillsPixelCentresInside() {
    Rig rig(DepthToolMode::Polygon);
    const QPoint corners[4] = {rig.at(50, 40), rig.at(250, 40), rig.at(250, 180), rig.at(50, 180)};
    for (const QPoint& c : corners) test::click(&rig.canvas, c);
    auto* tool = dynamic_cast<DepthTool*>(rig.canvas.tool());
    QCOMPARE(tool->polygonVertexCount(), 4);
    QTest::keyClick(&rig.canvas, Qt::Key_Return);
    QCOMPARE(tool->polygonVertexCount(), 0);
    QCOMPARE(rig.doc.undoStack()->count(), 1);
    // Independent: the polygon is the axis-aligned rectangle of the clicked image points.
    const Eigen::Vector2d lo = rig.image(corners[0]), hi = rig.image(corners[2]);
    for (int y = 0; y < 240; y += 5)
      for (int x = 0; x < 320; x += 5) {
        const bool inside = x + 0.5 >= lo.x() && x + 0.5 < hi.x() && y + 0.5 >= lo.y() &&
                            y + 0.5 < hi.y();
        QCOMPARE(rig.mask().at(x, y) == 255, inside);
      }
    // Closing on the first vertex with Alt erases.
    const QPoint inner[3] = {rig.at(100, 60), rig.at(200, 60), rig.at(150, 150)};
    for (const QPoint& c : inner) test::click(&rig.canvas, c);
    test::click(&rig.canvas, inner[0], Qt::AltModifier);
    QCOMPARE(rig.mask().at(150, 90), uint8_t{0});
    QCOMPARE(rig.mask().at(60, 170), uint8_t{255});
    QCOMPARE(rig.doc.undoStack()->count(), 2);
  }

  void threeDepthPointsGiveThePlane() {
    Rig rig(DepthToolMode::Polygon);
    for (QPoint c : {rig.at(0, 0), rig.at(320, 0), rig.at(320, 240), rig.at(0, 240)})
      test::click(&rig.canvas, c);
    QTest::keyClick(&rig.canvas, Qt::Key_Return);
    rig.use(DepthToolMode::Points);
    const double depths[3] = {4.0, 10.0, 25.0};
    const QPoint clicks[3] = {rig.at(30, 200), rig.at(290, 190), rig.at(160, 25)};
    DepthPanel panel(&rig.doc, &rig.settings, new DepthOverlay(&rig.doc, &rig.doc));
    for (int i = 0; i < 3; ++i) {
      rig.settings.setNextDepth(depths[i]);
      QVERIFY(!rig.doc.depth()->plane(0));
      test::click(&rig.canvas, clicks[i]);
    }
    QVERIFY2(rig.doc.depth()->plane(0), qPrintable(rig.doc.depth()->planeStatus(0)));
    QVERIFY(panel.statusText().contains("3 points"));
    const std::vector<DepthAnchor> anchors = rig.doc.depth()->layer(0).anchors;
    QCOMPARE(anchors.size(), size_t{3});
    for (int i = 0; i < 3; ++i) QCOMPARE(anchors[static_cast<size_t>(i)].depth, depths[i]);

    const ImageF depth = rig.doc.depth()->rasterise();
    for (int y = 3; y < 240; y += 17)
      for (int x = 5; x < 320; x += 19) {
        const double inverse = interpolatedInverseDepth(anchors, {x + 0.5, y + 0.5});
        const auto z = depthAt(depth, x, y);
        QVERIFY(z);
        // Beyond its points' depths (4 … 25) the plane keeps the nearer end of that span
        // (core/depth/inverse_depth_plane.h): never an extrapolation, a horizon or NaN.
        const double truth = inverse > 1.0 / 25.0 ? std::max(4.0, 1.0 / inverse) : 25.0;
        QVERIFY2(std::abs(*z - truth) < 1e-5 * truth, qPrintable(QString("%1 vs %2").arg(*z).arg(truth)));
      }

    // The next depth is typed key by key as a user types it (the panel's echo of each keystroke
    // must not re-format the text under the cursor: "1.5" once came out as 1).
    auto* next_depth = panel.findChild<QDoubleSpinBox*>("nextDepth");
    QVERIFY(next_depth);
    bool has_mnemonic = false;  // Alt+N focuses it
    for (const QLabel* label : panel.findChildren<QLabel*>())
      has_mnemonic = has_mnemonic || (label->buddy() == next_depth && label->text().contains("&N"));
    QVERIFY(has_mnemonic);
    for (const auto& [typed, value] : {std::pair{"1.5", 1.5}, std::pair{"0.75", 0.75},
                                       std::pair{"40", 40.0}, std::pair{"2.125", 2.125}}) {
      next_depth->selectAll();
      QTest::keyClicks(next_depth, typed);
      QCOMPARE(rig.settings.nextDepth(), value);
      QTest::keyClick(next_depth, Qt::Key_Tab);
      QCOMPARE(rig.settings.nextDepth(), value);
    }
    rig.settings.setNextDepth(3.0);  // set elsewhere ([ ] or a test): the box follows
    QCOMPARE(next_depth->value(), 3.0);
    auto* tolerance = panel.findChild<QDoubleSpinBox*>("edgeTolerance");
    QVERIFY(tolerance);
    tolerance->selectAll();
    QTest::keyClicks(tolerance, "0.15");
    QCOMPARE(rig.settings.edgeTolerance(), 0.15);

    // Typing a depth in the panel is an undoable edit and moves the plane.
    QTableWidget* table = panel.anchorTable();
    QCOMPARE(table->item(1, 2)->text().toDouble(), 10.0);
    const int steps = rig.doc.undoStack()->count();
    table->item(1, 2)->setText("12.5");
    QCOMPARE(rig.doc.depth()->layer(0).anchors[1].depth, 12.5);
    QCOMPARE(rig.doc.undoStack()->count(), steps + 1);
    table->item(1, 2)->setText("-3");  // refused, old value shown again
    QCOMPARE(rig.doc.depth()->layer(0).anchors[1].depth, 12.5);
    QCOMPARE(table->item(1, 2)->text().toDouble(), 12.5);
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.doc.depth()->layer(0).anchors[1].depth, 10.0);

    // A fourth click replaces the nearest point; on one line the status names the cause.
    rig.settings.setNextDepth(7.0);
    test::click(&rig.canvas, rig.at(150, 200));  // nearest: the first point
    QCOMPARE(rig.doc.depth()->layer(0).anchors[0].depth, 7.0);
    std::vector<DepthAnchor> line{{{10, 10}, 1}, {{100, 100}, 2}, {{200, 200}, 3}};
    rig.doc.undoStack()->push(new SetDepthAnchorsCommand(rig.doc.depth(), 0, line, "line"));
    QVERIFY(!rig.doc.depth()->plane(0));
    QVERIFY(panel.statusText().contains("one line"));
  }

  void overlayColoursByDepthWithALegendRange() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    DepthOverlay overlay(&doc);
    QVERIFY(overlay.image().isNull());
    DepthModel* depth = doc.depth();
    DepthPlaneLayer layer = depth->makeLayer();
    layer.mask.fillPolygon({{0, 0}, {160, 0}, {160, 240}, {0, 240}});
    // 1/z = 0.5 at x = 0 falling to 0.05 at x = 320 (z 2 … 20).
    layer.anchors = {{{0.0, 0.0}, 2.0}, {{320.0, 0.0}, 20.0}, {{0.0, 240.0}, 2.0}};
    doc.undoStack()->push(new AddDepthLayerCommand(depth, layer));
    overlay.update();
    QVERIFY(!overlay.image().isNull());
    // Covered pixels are the left half (centres 0.5 … 159.5): depth from 1/z = 0.5 − 0.45x/320.
    const double z_near = 1.0 / (0.5 - 0.45 * (0.5 * 320.0 / overlay.image().width()) / 320.0);
    QVERIFY(std::abs(overlay.minDepth() - z_near) < 1e-4);
    QVERIFY(overlay.maxDepth() > 3.5 && overlay.maxDepth() < 3.65);  // 1/z ≈ 0.275 at x ≈ 160
    const QImage img = overlay.image();
    QCOMPARE(qAlpha(img.pixel(img.width() - 2, img.height() / 2)), 0);  // right half: no depth
    const QColor near = img.pixelColor(0, 10), far = img.pixelColor(img.width() / 2 - 1, 10);
    QVERIFY(near.red() > far.red());
    QVERIFY(near.blue() < far.blue());
    overlay.setVisible(false);
    QVERIFY(!overlay.isVisible());
  }

  void projectFileKeepsDepth() {
    Project p;
    p.photo_path = dir_.filePath("photo.png");
    DepthPlaneLayer l;
    l.name = "Wall";
    l.mask = RegionMask(40, 30);
    l.mask.stamp({20, 15}, BrushOptions{9, 0.3, false});
    l.anchors = {{{1.0 / 3.0, 2.0}, 4.5}, {{30, 2}, 1e-3}, {{5, 25}, 12}};
    p.depth_layers = {l, DepthPlaneLayer{"Empty", RegionMask(40, 30), {}}};
    p.depth_map = DepthMapRef{dir_.filePath("depth.exr"), DepthFileOptions{0.001, true}};
    const QString path = dir_.filePath("depth.artcamproj");
    QVERIFY(writeProject(path, p).ok);
    const Result<Project> back = readProject(path);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(back->depth_layers == p.depth_layers);
    QVERIFY(back->depth_map);
    QCOMPARE(back->depth_map->path, p.depth_map->path);
    QCOMPARE(back->depth_map->options.scale, 0.001);
    QVERIFY(back->depth_map->options.inverse);
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(f.readAll().contains("\"version\": 2"));

    // Without depth the file stays version 1 (older studios open it); v1 files still read.
    Project plain;
    plain.photo_path = p.photo_path;
    QVERIFY(projectToJson(plain, path).contains("\"version\": 1"));
    QVERIFY(parseProject(R"({"format":"artcam-studio-project","version":1,"photo":"x.png"})",
                         "old.artcamproj")
                .ok());
    const auto bad = parseProject(
        R"({"format":"artcam-studio-project","version":2,"photo":"x.png",
            "depth":{"layers":[{"name":"a","size":[4,4],"mask":"AAE="}]}})",
        "p.artcamproj");
    QVERIFY(!bad.ok());
    QVERIFY2(bad.status.message.find("p.artcamproj: /depth/layers/0/mask") == 0,
             bad.status.message.c_str());
    const auto bad_depth = parseProject(
        R"({"format":"artcam-studio-project","version":2,"photo":"x.png",
            "depth":{"layers":[{"name":"a","size":[1,1],"mask":"AAE=",
                                "anchors":[{"pixel":[0,0],"depth":0}]}]}})",
        "p.artcamproj");
    QVERIFY(!bad_depth.ok());
    QVERIFY2(bad_depth.status.message.find("/depth/layers/0/anchors/0/depth") != std::string::npos,
             bad_depth.status.message.c_str());
  }

  void depthMapLoadsOffThreadAsAnUndoableEdit() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(test::syntheticPhoto());
    // A float EXR at half the photo's size: depth 3 + x/100 (of its own pixels).
    ImageF map(160, 120, 1);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) map.pixel(x, y)[0] = 3.0f + static_cast<float>(x) / 100.0f;
    const QString exr = dir_.filePath("depth.exr");
    WriteImageOptions as_float;
    as_float.pixel_type = "float";
    QVERIFY(writeImage(exr.toStdString(), map, nullptr, as_float).ok);

    QSignalSpy loaded(&session, &Session::depthMapLoaded);
    session.loadDepthMap(exr, {});
    QVERIFY(!doc.depth()->map());  // not yet: it is read on a worker thread
    QTRY_COMPARE_WITH_TIMEOUT(loaded.size(), 1, 20000);
    QVERIFY2(loaded.front().at(0).toBool(), qPrintable(loaded.front().at(1).toString()));
    QVERIFY(doc.depth()->map());
    QVERIFY(doc.depth()->hasDepth());
    const ImageF depth = doc.depth()->rasterise();
    // Photo pixel (101, 7) samples map pixel (50, 3).
    QVERIFY(std::abs(*depthAt(depth, 101, 7) - 3.5) < 1e-6);
    QCOMPARE(doc.undoStack()->count(), 1);
    doc.undoStack()->undo();
    QVERIFY(!doc.depth()->map());

    // A map of another aspect is refused, naming both sizes.
    ImageF wide(200, 50, 1);
    std::fill(wide.data.begin(), wide.data.end(), 1.0f);
    const QString bad = dir_.filePath("wide.exr");
    QVERIFY(writeImage(bad.toStdString(), wide, nullptr, as_float).ok);
    QSignalSpy errors(&session, &Session::errorOccurred);
    session.loadDepthMap(bad, {});
    QTRY_COMPARE_WITH_TIMEOUT(errors.size(), 1, 20000);
    QVERIFY(errors.front().front().toString().contains("200×50"));
    QVERIFY(!doc.depth()->map());
  }

  void sessionSavesAndReopensDepth() {
    const QString photo = dir_.filePath("photo.png");
    QVERIFY(writeImage(photo.toStdString(), test::syntheticPhoto()->full.image).ok);
    ImageF map(320, 240, 1);
    std::fill(map.data.begin(), map.data.end(), 42.0f);
    const QString exr = dir_.filePath("flat.exr");
    WriteImageOptions as_float;
    as_float.pixel_type = "float";
    QVERIFY(writeImage(exr.toStdString(), map, nullptr, as_float).ok);

    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.openPhoto(photo);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    DepthPlaneLayer layer = doc.depth()->makeLayer();
    layer.mask.stamp({100, 100}, BrushOptions{30, 0.5, false});
    layer.anchors = {{{80, 90}, 3}, {{120, 95}, 4}, {{100, 130}, 5}};
    doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), layer));
    QSignalSpy loaded(&session, &Session::depthMapLoaded);
    session.loadDepthMap(exr, {});
    QTRY_COMPARE_WITH_TIMEOUT(loaded.size(), 1, 20000);
    const QString project = dir_.filePath("with-depth.artcamproj");
    QVERIFY(ui::test::saveAndWait(session, project));

    Document doc2;
    Session session2(&doc2, nullptr);
    session2.setInteractive(false);
    session2.openProject(project);
    QTRY_VERIFY_WITH_TIMEOUT(doc2.photo() != nullptr && doc2.depth()->map(), 20000);
    QVERIFY(doc2.depth()->layers() == doc.depth()->layers());
    QCOMPARE(doc2.depth()->map()->path, exr);
    QVERIFY(!doc2.isModified());  // opening is not an edit
    const ImageF a = doc.depth()->rasterise(), b = doc2.depth()->rasterise();
    QVERIFY(a.data == b.data);
  }

  void layersOfAnotherSizeAreReportedNotSilentlyDropped() {
    const QString photo = dir_.filePath("photo-for-size.png");
    QVERIFY(writeImage(photo.toStdString(), test::syntheticPhoto()->full.image).ok);
    Project p;
    p.photo_path = photo;
    p.depth_layers = {DepthPlaneLayer{"Old", RegionMask(100, 80), {}}};
    const QString project = dir_.filePath("resized.artcamproj");
    QVERIFY(writeProject(project, p).ok);
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy errors(&session, &Session::errorOccurred);
    session.openProject(project);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    QCOMPARE(errors.size(), 1);
    const QString message = errors.front().front().toString();
    QVERIFY2(message.contains("resized.artcamproj: /depth/layers/0") && message.contains("100×80") &&
                 message.contains("320×240"),
             qPrintable(message));
    QCOMPARE(doc.depth()->layerCount(), 0);
  }
};

QTEST_MAIN(TestDepthPlanes)
#include "test_depth_planes.moc"
