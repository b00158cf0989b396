// SPDX-License-Identifier: Apache-2.0
// `artcam sample` and `artcam insert`, run as processes: the ray-traced sample's grid matches
// fit, the graphic lands inside the reflection and nowhere else, a saved piecewise camera
// gives the same result, and bad input leaves no output behind.
#include "core/io/image_io.h"
#include "core/io/artcam_file.h"
#include "core/piecewise/sample_scenes.h"

#include "tests/app/cli_run.h"
#include "tests/app/glass_of_water_truth.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QTemporaryDir>
#include <algorithm>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

ImageF load(const QString& path) {
  const auto r = readImage(path.toStdString());
  return r ? r->image : ImageF();
}

// The rows of a src_x,src_y,dst_x,dst_y file, read here without the engine's reader.
QVector<QVector<double>> readMatchesCsvForTest(const QString& path) {
  QVector<QVector<double>> rows;
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) return rows;
  file.readLine();  // header
  while (!file.atEnd()) {
    const QList<QByteArray> fields = file.readLine().trimmed().split(',');
    if (fields.size() != 4) continue;
    QVector<double> row;
    for (const QByteArray& f : fields) row.push_back(f.toDouble());
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

class TestCliInsert : public QObject {
  Q_OBJECT

 private slots:
  void insertsIntoTheReflectionOnly() {
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "mirror-sphere", "-o", dir.path(), "--size", "320x240"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"insert", dir.filePath("mirror-sphere.png"), dir.filePath("emblem.png"),
                   "--matches", dir.filePath("mirror-sphere-grid.csv"), "--max-error", "0.3",
                   "--save-camera", dir.filePath("sphere.artcam"), "-o", dir.filePath("out.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("patches"));

    const ImageF before = load(dir.filePath("mirror-sphere.png"));
    const ImageF after = load(dir.filePath("out.png"));
    QCOMPARE(after.width, 320);
    QCOMPARE(after.height, 240);
    // The scene as the sample command made it (same parameters), traced here.
    MirrorSphereScene scene;
    scene.photo_width = 320;
    scene.photo_height = 240;
    scene.focal_px = 0.9 * 320;
    scene.floor_centre_z = 1.6;
    int changed_inside = 0, changed_outside = 0;
    for (int y = 0; y < 240; ++y)
      for (int x = 0; x < 320; ++x) {
        double diff = 0;
        for (int c = 0; c < 3; ++c) diff = std::max(diff, double(std::abs(after.pixel(x, y)[c] - before.pixel(x, y)[c])));
        if (diff < 0.02) continue;
        // Inside: this pixel or a neighbour sees the board through the sphere.
        bool near = false;
        for (int dy = -1; dy <= 1 && !near; ++dy)
          for (int dx = -1; dx <= 1 && !near; ++dx)
            near = scene.graphicFromPhoto({x + dx + 0.5, y + dy + 0.5}).has_value();
        (near ? changed_inside : changed_outside) += 1;
      }
    QVERIFY2(changed_inside > 300, qPrintable(QString::number(changed_inside)));
    QCOMPARE(changed_outside, 0);

    // The saved piecewise camera reproduces the same image.
    const auto saved = readArtcam(dir.filePath("sphere.artcam").toStdString());
    QVERIFY2(saved.ok(), saved.status.message.c_str());
    QVERIFY(saved->pieces && saved->pieces->patches.size() > 1);
    r = artcamCli({"insert", dir.filePath("mirror-sphere.png"), dir.filePath("emblem.png"),
                   "--camera", dir.filePath("sphere.artcam"), "-o", dir.filePath("again.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ImageF again = load(dir.filePath("again.png"));
    QCOMPARE(again.data, after.data);
  }

  void insertsOnTheTableToo() {
    // Fig 7(c): with the sample's four table clicks and the sphere's outline, the emblem shows on
    // the table where the photo sees the board directly, and in the reflection; nowhere else.
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "mirror-sphere", "-o", dir.path(), "--size", "320x240"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"insert", dir.filePath("mirror-sphere.png"), dir.filePath("emblem.png"),
                   "--matches", dir.filePath("mirror-sphere-grid.csv"), "--table",
                   dir.filePath("mirror-sphere-table.csv"), "--region",
                   dir.filePath("mirror-sphere-region.csv"), "-o", dir.filePath("out.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("table homography"));
    const ImageF before = load(dir.filePath("mirror-sphere.png"));
    const ImageF after = load(dir.filePath("out.png"));
    MirrorSphereScene scene;
    scene.photo_width = 320;
    scene.photo_height = 240;
    scene.focal_px = 0.9 * 320;
    scene.floor_centre_z = 1.6;
    int on_table = 0, in_reflection = 0, elsewhere = 0;
    for (int y = 0; y < 240; ++y)
      for (int x = 0; x < 320; ++x) {
        double diff = 0;
        for (int c = 0; c < 3; ++c)
          diff = std::max(diff, double(std::abs(after.pixel(x, y)[c] - before.pixel(x, y)[c])));
        if (diff < 0.02) continue;
        bool table = false, reflection = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const TracedRay t = scene.trace({x + dx + 0.5, y + dy + 0.5});
            const bool on_board = t.on_plane && t.plane_px.x() >= 0 && t.plane_px.y() >= 0 &&
                                  t.plane_px.x() <= 512 && t.plane_px.y() <= 512;
            table = table || (on_board && !t.through_object);
            reflection = reflection || (on_board && t.through_object);
          }
        if (table) ++on_table;
        else if (reflection) ++in_reflection;
        else ++elsewhere;
      }
    QVERIFY2(on_table > 5000, qPrintable(QString::number(on_table)));
    QVERIFY2(in_reflection > 300, qPrintable(QString::number(in_reflection)));
    QCOMPARE(elsewhere, 0);

    // --grid-on-table: the same grid given as photographed on the table (Fig 7a) is taken to the
    // canonical view by the table homography and gives the same picture.
    const auto grid = readMatchesCsvForTest(dir.filePath("mirror-sphere-grid.csv"));
    QVERIFY(!grid.isEmpty());
    QFile on_table_csv(dir.filePath("grid-on-table.csv"));
    QVERIFY(on_table_csv.open(QIODevice::WriteOnly));
    on_table_csv.write("src_x,src_y,dst_x,dst_y\n");
    for (const QVector<double>& row : grid) {
      const Eigen::Vector2d seen = scene.photoFromWorld(scene.floorFromGraphicPx({row[0], row[1]}));
      on_table_csv.write(QString("%1,%2,%3,%4\n")
                             .arg(seen.x(), 0, 'g', 17).arg(seen.y(), 0, 'g', 17)
                             .arg(row[2], 0, 'g', 17).arg(row[3], 0, 'g', 17).toUtf8());
    }
    on_table_csv.close();
    r = artcamCli({"insert", dir.filePath("mirror-sphere.png"), dir.filePath("emblem.png"),
                   "--matches", dir.filePath("grid-on-table.csv"), "--grid-on-table", "--table",
                   dir.filePath("mirror-sphere-table.csv"), "--region",
                   dir.filePath("mirror-sphere-region.csv"), "-o", dir.filePath("again.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ImageF again = load(dir.filePath("again.png"));
    double worst = 0;
    for (size_t i = 0; i < again.data.size(); ++i)
      worst = std::max(worst, double(std::abs(again.data[i] - after.data[i])));
    QVERIFY2(worst < 0.02, qPrintable(QString::number(worst)));

    QCOMPARE(artcamCli({"insert", dir.filePath("mirror-sphere.png"), dir.filePath("emblem.png"),
                        "--matches", dir.filePath("mirror-sphere-grid.csv"), "--grid-on-table",
                        "-o", dir.filePath("x.png")}).exit_code, 2);
  }

  // Fig 8 whole: `artcam sample glass-of-water` and two inserts, through the water and then
  // through the air above it, put the graphic where the ray tracer sees it through each: in
  // every interior pixel of both regions the result is the graphic sampled at the traced
  // backdrop point, over the photo (computed here from the tracer and the two files; linear
  // light, so the 8-bit files' rounding and the resampling's domain leave a little).
  void insertsThroughAirAndWaterOfOneGlass() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    Run r = artcamCli({"sample", "glass-of-water", "-o", dir.path(), "--size", "320x240"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(QFile::exists(dir.filePath("glass-of-water-air-grid.csv")));
    r = artcamCli({"insert", dir.filePath("glass-of-water.png"), dir.filePath("emblem.png"),
                   "--matches", dir.filePath("glass-of-water-grid.csv"), "-o",
                   dir.filePath("water.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"insert", dir.filePath("water.png"), dir.filePath("emblem.png"), "--matches",
                   dir.filePath("glass-of-water-air-grid.csv"), "-o", dir.filePath("both.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ImageF photo = load(dir.filePath("glass-of-water.png"));
    const ImageF emblem = load(dir.filePath("emblem.png"));
    const ImageF both = load(dir.filePath("both.png"));
    QVERIFY(!photo.empty() && !emblem.empty() && both.width == 320);
    for (const auto medium : {GlassOfWaterScene::Medium::Water, GlassOfWaterScene::Medium::Air}) {
      const artcam::test::TracerComparison c = artcam::test::compareWithTracer(
          photo, emblem, both, artcam::test::sampleGlassOfWater320(), medium);
      qInfo(
          "glass of water, through %s: mean %.4f against the tracer over %lld px (the graphic "
          "changes them by %.3f)",
          medium == GlassOfWaterScene::Medium::Water ? "water" : "air", c.mean, c.pixels, c.change);
      QVERIFY(c.pixels > 300);
      // A camera of the other medium, or none, is off by about the change itself.
      QVERIFY2(c.mean < 0.02 && c.change > 8 * c.mean,
               qPrintable(QString("mean %1, change %2").arg(c.mean).arg(c.change)));
    }
  }

  void fitPiecewiseMeetsItsThreshold() {
    QTemporaryDir dir;
    QVERIFY(artcamCli({"sample", "water-glass", "-o", dir.path()}).exit_code == 0);
    const Run r = artcamCli({"fit", "--piecewise", dir.filePath("water-glass-grid.csv"), "--size",
                             "512x512", "--target-size", "640x480", "--max-error", "0.2", "-o",
                             dir.filePath("glass.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("patch 0"));
    const auto doc = readArtcam(dir.filePath("glass.artcam").toStdString());
    QVERIFY2(doc.ok(), doc.status.message.c_str());
    QVERIFY(doc->pieces.has_value());
    // Every grid match, read back from the file the sample wrote, within the threshold.
    QVERIFY(!doc->matches.empty());
    for (const PointMatch& m : doc->matches) {
      const auto y = doc->pieces->targetPixelFromSourcePixel(m.source);
      QVERIFY(y);
      QVERIFY2((*y - m.target).norm() <= 0.2 + 1e-9, qPrintable(QString::number((*y - m.target).norm())));
    }
    // artcam warp renders the patches (mesh warp), not the top-level single camera.
    const Run w = artcamCli({"warp", dir.filePath("emblem.png"), dir.filePath("glass.artcam"), "-o",
                             dir.filePath("warped.png")});
    QVERIFY2(w.exit_code == 0, qPrintable(w.err));
    QVERIFY(w.out.contains("piecewise"));
    const ImageF warped = load(dir.filePath("warped.png"));
    QCOMPARE(warped.width, 640);
    QCOMPARE(warped.height, 480);
    QCOMPARE(artcamCli({"fit", "--max-error", "0.2", dir.filePath("water-glass-grid.csv"), "--size",
                        "512x512", "-o", dir.filePath("x.artcam")}).exit_code, 2);
  }

  void badInputLeavesNothingBehind() {
    QTemporaryDir dir;
    QVERIFY(artcamCli({"sample", "water-glass", "-o", dir.path(), "--size", "160x120"}).exit_code == 0);
    QFile csv(dir.filePath("few.csv"));
    QVERIFY(csv.open(QIODevice::WriteOnly));
    csv.write("src_x,src_y,dst_x,dst_y\n1,2,3,4\n5,6,7,8\n");
    csv.close();
    Run r = artcamCli({"insert", dir.filePath("water-glass.png"), dir.filePath("emblem.png"),
                       "--matches", dir.filePath("few.csv"), "-o", dir.filePath("out.png")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("few.csv"));
    QVERIFY(r.err.contains("at least"));
    QVERIFY(!QFile::exists(dir.filePath("out.png")));

    r = artcamCli({"insert", dir.filePath("water-glass.png"), dir.filePath("emblem.png"),
                   "--matches", dir.filePath("water-glass-grid.csv"), "-o",
                   dir.filePath("water-glass.png")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("refusing to overwrite"));

    r = artcamCli({"insert", dir.filePath("water-glass.png"), dir.filePath("emblem.png"), "-o",
                   dir.filePath("out.png")});
    QCOMPARE(r.exit_code, 2);
    r = artcamCli({"sample", "teapot", "-o", dir.path()});
    QCOMPARE(r.exit_code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliInsert)
#include "test_cli_insert.moc"
