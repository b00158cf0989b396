// SPDX-License-Identifier: Apache-2.0
// The unfolded view in the studio (Unfold ▸ Wall Tool, Unfold Walls…; the paper's Fig 2) on the
// bundled house: its left view opened, the depth made from the pair (File ▸ Depth from Stereo
// Pair…), the walls clicked with the wall tool in any order and from any corner, then unfolded.
// The tool's walls are the sample's own outlines (base first, left to right); the studio's
// camera is core's unfoldWalls on the document's depth in the photo's frame; its export is the
// command line's unfolded picture, moved into that frame and not stretched; the walls are kept
// in the project; undo takes the camera away; without depth the unfold is refused in one line.
#include "core/io/image_io.h"
#include "core/io/walls_csv.h"
#include "core/piecewise/unfold_walls.h"
#include "tests/app/cli_run.h"
#include "ui/canvas.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/session.h"
#include "ui/unfold/unfold_studio.h"
#include "ui/unfold/wall_tool.h"
#include "ui/unfold/walls_model.h"

#include <QAction>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>

using namespace artcam;
using namespace artcam::ui;

namespace {

bool openAndWait(MainWindow& window, const QString& photo) {
  window.session()->setInteractive(false);
  window.session()->openPhoto(photo);
  Document* doc = window.document();
  return QTest::qWaitFor([doc] { return doc->photo() && doc->photo()->hasFullImage(); }, 30000);
}

// Clicks an outline's corners with the wall tool, starting at corner `first`, walking the other
// way round when `reversed`, and closes it with Enter.
void clickWall(Canvas* canvas, const std::vector<Eigen::Vector2d>& corners, size_t first,
               bool reversed) {
  const size_t n = corners.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = reversed ? (first + n - k) % n : (first + k) % n;
    const QPointF w = canvas->view().widgetFromImage(QPointF(corners[i].x(), corners[i].y()));
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, w.toPoint());
  }
  QTest::keyClick(canvas, Qt::Key_Return);
}

double meanDifference(const ImageF& a, const ImageF& b, int dy, long long* counted) {
  double sum = 0.0;
  long long n = 0;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) {
      const float* p = a.pixel(x, y + dy);
      const float* q = b.pixel(x, y);
      if (p[3] < 0.999f || q[3] < 0.999f) continue;
      for (int c = 0; c < 3; ++c) sum += std::abs(p[c] - q[c]);
      ++n;
    }
  *counted = n;
  return n ? sum / (3.0 * n) : 1.0;
}

}  // namespace

class TestUnfoldStudio : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    // This test's own settings: no export options or focal length of another run.
    QStandardPaths::setTestModeEnabled(true);
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, dir_.filePath("settings"));
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, dir_.filePath("settings"));
    const auto made = artcam::test::artcamCli({"sample", "stereo-house", "-o", path("house")});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
  }

  void wallsUnfoldAsOnTheCommandLine() {
    MainWindow window;
    window.resize(1200, 800);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(openAndWait(window, path("house/house-left.png")));
    Document* doc = window.document();
    auto* unfold = window.findChild<UnfoldStudio*>();
    QVERIFY(unfold);
    unfold->setInteractive(false);
    QSignalSpy unfolded(unfold, &UnfoldStudio::unfolded);

    // Without depth: refused, saying where depth comes from.
    const auto outlines = readWallsCsv(path("house/house-walls.csv").toStdString());
    QVERIFY(outlines.ok());
    QCOMPARE(outlines->size(), size_t{2});
    unfold->walls()->setWalls(*outlines);
    unfold->unfold(560.0);
    QCOMPARE(unfolded.size(), 1);
    QVERIFY(!unfolded.last().at(0).toBool());
    QVERIFY2(unfolded.last().at(1).toString().contains("Depth from Stereo Pair"),
             qPrintable(unfolded.last().at(1).toString()));
    unfold->walls()->setWalls({});

    QSignalSpy depth_loaded(window.session(), &Session::depthMapLoaded);
    window.session()->depthFromStereo(path("house/house-right.png"), 140.0, path("depth.exr"));
    QVERIFY(depth_loaded.wait(60000));
    QVERIFY(depth_loaded.first().at(0).toBool());

    // The wall tool: the gable end first, from its apex the other way round; then the front
    // from its top-right corner. The model turns each to its base and sorts them.
    unfold->wallToolAction()->trigger();
    Canvas* canvas = window.canvas();
    QVERIFY(dynamic_cast<WallTool*>(canvas->tool()));
    clickWall(canvas, (*outlines)[1].photo_px, 3, /*reversed=*/true);
    clickWall(canvas, (*outlines)[0].photo_px, 2, /*reversed=*/false);
    const std::vector<WallOutline>& walls = unfold->walls()->walls();
    QCOMPARE(walls.size(), size_t{2});
    const double pixel = 1.0 / canvas->view().scale();  // one widget pixel, in photo pixels
    for (size_t w = 0; w < 2; ++w) {
      QCOMPARE(walls[w].photo_px.size(), (*outlines)[w].photo_px.size());
      for (size_t k = 0; k < walls[w].photo_px.size(); ++k)
        QVERIFY2((walls[w].photo_px[k] - (*outlines)[w].photo_px[k]).norm() < pixel,
                 qPrintable(QString("wall %1 corner %2").arg(w).arg(k)));
    }
    QCOMPARE(doc->undoStack()->count() >= 3, true);  // depth, two walls

    unfold->unfold(560.0);
    QVERIFY(unfolded.wait(30000));
    QVERIFY2(unfolded.last().at(0).toBool(), qPrintable(unfolded.last().at(1).toString()));
    QVERIFY2(unfolded.last().at(1).toString().contains("roof"),
             qPrintable(unfolded.last().at(1).toString()));
    QVERIFY(doc->manualCamera());
    QVERIFY(doc->manualCamera()->pieces);
    QCOMPARE(doc->manualCamera()->pieces->target_size, doc->photo()->size());

    // The same camera as core's, on the document's depth, in the photo's frame.
    UnfoldOptions options;
    options.focal_px = 560.0;
    options.frame = doc->photo()->size();
    const ImageF depth = doc->depth()->rasterise();
    const auto core = unfoldWalls(depth, doc->photo()->size(), walls, options);
    QVERIFY(core.ok());
    QCOMPARE(doc->manualCamera()->pieces->patches.size(), core->pieces->patches.size());
    int mapped = 0;
    for (int y = 0; y < 480; y += 8)
      for (int x = 0; x < 640; x += 8) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        const auto a = doc->manualCamera()->pieces->targetPixelFromSourcePixel(p);
        const auto b = core->pieces->targetPixelFromSourcePixel(p);
        QCOMPARE(a.has_value(), b.has_value());
        if (a) {
          QVERIFY2((*a - *b).norm() < 1e-9, qPrintable(QString("at %1,%2").arg(x).arg(y)));
          ++mapped;
        }
      }
    QVERIFY(mapped > 1000);

    // Exported, it is the command line's picture (the sample's own outlines, no frame) at the
    // top of the photo's frame: the same scale, nothing stretched, transparent below.
    window.session()->setExportOptions(ExportOptions{});  // transparent where nothing maps
    QSignalSpy exported(window.session(), &Session::exportFinished);
    window.session()->exportImage(path("studio-unfolded.png"));
    QVERIFY(exported.wait(30000));
    QVERIFY2(exported.last().at(0).toBool(), qPrintable(exported.last().at(1).toString()));
    auto cli = artcam::test::artcamCli({"unfold", path("house/house-left.png"), "--depth",
                                        path("depth.exr"), "--walls", path("house/house-walls.csv"),
                                        "--focal", "560", "-o", path("cli.artcam")});
    QVERIFY2(cli.exit_code == 0, qPrintable(cli.err));
    cli = artcam::test::artcamCli(
        {"warp", path("house/house-left.png"), path("cli.artcam"), "-o", path("cli-unfolded.png")});
    QVERIFY2(cli.exit_code == 0, qPrintable(cli.err));
    const auto studio_png = readImage(path("studio-unfolded.png").toStdString());
    const auto cli_png = readImage(path("cli-unfolded.png").toStdString());
    QVERIFY(studio_png.ok() && cli_png.ok());
    QCOMPARE(studio_png->image.width, 640);
    QCOMPARE(studio_png->image.height, 480);
    QCOMPARE(cli_png->image.width, 640);
    const int dy = 0;
    long long n = 0;
    const double moved = meanDifference(studio_png->image, cli_png->image, dy, &n);
    long long n_off = 0;
    const double off = meanDifference(studio_png->image, cli_png->image, dy + 3, &n_off);
    qInfo(
        "studio export vs the command line's: mean |difference| %.4f over %lld px (3 rows "
        "off: %.4f)",
        moved, n, off);
    QVERIFY(n > 100000);
    QVERIFY2(moved < 0.01, qPrintable(QString::number(moved)));
    QVERIFY2(moved < 0.25 * off, qPrintable(QString("%1 vs %2").arg(moved).arg(off)));
    for (int y = cli_png->image.height + 2; y < 480; y += 5)
      for (int x = 0; x < 640; x += 7) QCOMPARE(studio_png->image.pixel(x, y)[3], 0.0f);

    // Kept in the project.
    QSignalSpy saved(window.session(), &Session::projectSaved);
    QVERIFY(window.session()->saveProjectTo(path("house.artcamproj")));
    QVERIFY(saved.wait(30000));
    QVERIFY(saved.last().at(0).toBool());
    {
      MainWindow reopened;
      reopened.session()->setInteractive(false);
      QSignalSpy opened(reopened.session(), &Session::projectOpened);
      reopened.session()->openProject(path("house.artcamproj"));
      QVERIFY(opened.wait(30000));
      auto* again = reopened.findChild<UnfoldStudio*>();
      QVERIFY(QTest::qWaitFor([again] { return again->walls()->walls().size() == 2; }, 10000));
      for (size_t w = 0; w < 2; ++w)
        QCOMPARE(again->walls()->walls()[w].photo_px, walls[w].photo_px);
      QVERIFY(reopened.document()->manualCamera() && reopened.document()->manualCamera()->pieces);
    }

    // Undo takes the unfold away; the walls stay.
    doc->undoStack()->undo();
    QVERIFY(!doc->manualCamera());
    QCOMPARE(unfold->walls()->walls().size(), size_t{2});
  }

  void baseFirstAndOrder() {
    // A quadrilateral clicked from its top-left corner anticlockwise on screen.
    WallOutline w{"w", {{10, 10}, {8, 60}, {70, 62}, {72, 12}}};
    const WallOutline t = withBaseFirst(w);
    QCOMPARE(t.photo_px[0], Eigen::Vector2d(8, 60));
    QCOMPARE(t.photo_px[1], Eigen::Vector2d(70, 62));
    // Clicked the other way round: the base still runs left to right.
    WallOutline r{"r", {{10, 10}, {72, 12}, {70, 62}, {8, 60}}};
    const WallOutline u = withBaseFirst(r);
    QCOMPARE(u.photo_px[0], Eigen::Vector2d(8, 60));
    QCOMPARE(u.photo_px[1], Eigen::Vector2d(70, 62));
    QCOMPARE(u.photo_px.size(), size_t{4});
    const auto sorted = leftToRight({{"right", {{100, 0}, {120, 0}, {110, 9}}}, w});
    QCOMPARE(sorted[0].name, std::string("w"));
  }

  void projectPartRefusesBadWalls() {
    const FrameSize photo{640, 480};
    QJsonObject bad{{"walls", QJsonArray{QJsonObject{
                                  {"name", "a"},
                                  {"corners", QJsonArray{QJsonArray{1, 2}, QJsonArray{3, 4}}}}}}};
    auto r = wallsFromJson(bad, photo, "p: /parts/walls");
    QVERIFY(!r.ok());
    QVERIFY2(QString::fromStdString(r.status.message).contains("/walls/0/corners"),
             r.status.message.c_str());
    QJsonObject outside{
        {"walls", QJsonArray{QJsonObject{{"name", "a"},
                                         {"corners", QJsonArray{QJsonArray{1, 2}, QJsonArray{3, 4},
                                                                QJsonArray{9000, 4}}}}}}};
    r = wallsFromJson(outside, photo, "p: /parts/walls");
    QVERIFY(!r.ok());
    QVERIFY2(QString::fromStdString(r.status.message).contains("/walls/0/corners/2"),
             r.status.message.c_str());
    const std::vector<WallOutline> good{{"a", {{1, 2}, {3, 4}, {5, 1}}}};
    const auto back = wallsFromJson(wallsToJson(good), photo, "p");
    QVERIFY(back.ok());
    QCOMPARE(back->front().photo_px, good.front().photo_px);
  }
};

QTEST_MAIN(TestUnfoldStudio)
#include "test_unfold_studio.moc"
