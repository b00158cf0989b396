// SPDX-License-Identifier: Apache-2.0
// `artcam compose`, run as a process: a homography then a rational camera become one camera
// that maps pixels as the two files do one after the other (read back and evaluated here).
#include "core/io/artcam_file.h"
#include "core/model/frames.h"
#include "tests/app/cli_run.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QTemporaryDir>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

void writeCamera(const QString& path, const Camera& camera) {
  const Status s = writeArtcam(path.toStdString(), Artcam(camera));
  QVERIFY2(s.ok, s.message.c_str());
}

}  // namespace

class TestCliCompose : public QObject {
  Q_OBJECT

 private slots:
  void composesAFileChain() {
    QTemporaryDir dir;
    const Camera view_to_table = test::randomHomographyCamera({800, 600}, {640, 480});
    const Camera table_to_reflection = test::randomRationalCamera({640, 480}, {640, 480});
    const Camera second_lens = test::randomRationalCamera({640, 480}, {640, 480}, 0.03);
    writeCamera(dir.filePath("h.artcam"), view_to_table);
    writeCamera(dir.filePath("r.artcam"), table_to_reflection);
    writeCamera(dir.filePath("s.artcam"), second_lens);

    const Run r = artcamCli({"compose", dir.filePath("h.artcam"), dir.filePath("r.artcam"),
                             dir.filePath("s.artcam"), "-o", dir.filePath("c.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("homography"));
    const auto doc = readArtcam(dir.filePath("c.artcam").toStdString());
    QVERIFY2(doc.ok(), doc.status.message.c_str());
    // h folds into r (one stage), then the second lens chains: two stages.
    QCOMPARE(doc->main().stages().size(), size_t{2});
    QCOMPARE(doc->main().sourceSize(), (FrameSize{800, 600}));
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector2d p(test::uniform(40, 760), test::uniform(30, 570));
      const auto expected = targetPixelFromSourcePixel(
          second_lens, *targetPixelFromSourcePixel(
                           table_to_reflection, *targetPixelFromSourcePixel(view_to_table, p)));
      const auto got = targetPixelFromSourcePixel(doc->main(), p);
      QVERIFY(expected && got);
      QVERIFY((*got - *expected).norm() < 1e-8);
    }
  }

  void composesAHomographyBeforeAPiecewiseCamera() {
    // The paper's §5 direction through files: a fitted piecewise lens after a homography. The
    // written camera keeps its patches (with the patch frame) and maps as the two files do.
    QTemporaryDir dir;
    QFile csv(dir.filePath("lens.csv"));
    QVERIFY(csv.open(QIODevice::WriteOnly));
    csv.write("src_x,src_y,dst_x,dst_y\n");
    for (int j = 0; j <= 20; ++j)
      for (int i = 0; i <= 30; ++i) {
        const Eigen::Vector2d s(600.0 * i / 30, 400.0 * j / 20), d = (s - Eigen::Vector2d(300, 200)) / 300;
        const double r2 = d.squaredNorm();
        const Eigen::Vector2d t = Eigen::Vector2d(300, 200) + 300 * d * (1 - 0.12 * r2 + 0.06 * r2 * r2);
        csv.write(QString("%1,%2,%3,%4\n").arg(s.x()).arg(s.y()).arg(t.x(), 0, 'g', 17).arg(t.y(), 0, 'g', 17).toUtf8());
      }
    csv.close();
    Run r = artcamCli({"fit", "--piecewise", dir.filePath("lens.csv"), "--size", "600x400", "--max-error", "0.1",
                       "-o", dir.filePath("p.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    test::rng().seed(3);
    const Camera h = test::randomHomographyCamera({450, 300}, {600, 400});
    writeCamera(dir.filePath("h.artcam"), h);
    r = artcamCli({"compose", dir.filePath("h.artcam"), dir.filePath("p.artcam"), "-o", dir.filePath("hp.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("patches") && r.out.contains("piecewise camera"), qPrintable(r.out));
    const auto p = readArtcam(dir.filePath("p.artcam").toStdString());
    const auto hp = readArtcam(dir.filePath("hp.artcam").toStdString());
    QVERIFY(p.ok() && hp.ok() && p->pieces && hp->pieces && hp->pieces->patch_frame);
    int mapped = 0;
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector2d x(test::uniform(5, 445), test::uniform(5, 295));
      const auto mid = targetPixelFromSourcePixel(h, x);
      const auto expected = mid ? p->pieces->targetPixelFromSourcePixel(*mid) : std::nullopt;
      const auto got = hp->pieces->targetPixelFromSourcePixel(x);
      QCOMPARE(got.has_value(), expected.has_value());
      if (!got) continue;
      ++mapped;
      QVERIFY2((*got - *expected).norm() < 1e-6, qPrintable(QString::number((*got - *expected).norm())));
    }
    QVERIFY(mapped > 20);
  }

  void refusesFramesOfAnotherShape() {
    // A camera made for 4:3 after one whose target is 3:2: refused, both frames named, nothing written.
    QTemporaryDir dir;
    writeCamera(dir.filePath("a.artcam"), test::randomHomographyCamera({600, 400}, {600, 400}));
    writeCamera(dir.filePath("b.artcam"), test::randomRationalCamera({640, 480}, {640, 480}));
    const Run r = artcamCli({"compose", dir.filePath("a.artcam"), dir.filePath("b.artcam"), "-o", dir.filePath("c.artcam")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("600x400") && r.err.contains("640x480") && r.err.contains("another shape"), qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("c.artcam")));
  }

  void refusesToOverwriteAnInputAndNamesBadFiles() {
    QTemporaryDir dir;
    writeCamera(dir.filePath("a.artcam"), test::randomRationalCamera({64, 64}, {64, 64}));
    const QByteArray before = [&] {
      QFile f(dir.filePath("a.artcam"));
      return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    }();
    Run r = artcamCli({"compose", dir.filePath("a.artcam"), dir.filePath("a.artcam"), "-o",
                       dir.filePath("a.artcam")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("refusing to overwrite"));
    QFile f(dir.filePath("a.artcam"));
    QVERIFY(f.open(QIODevice::ReadOnly));
    QCOMPARE(f.readAll(), before);

    r = artcamCli({"compose", dir.filePath("a.artcam"), dir.filePath("missing.artcam"), "-o",
                   dir.filePath("out.artcam")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("missing.artcam"));
    QVERIFY(!QFile::exists(dir.filePath("out.artcam")));

    r = artcamCli({"compose", dir.filePath("a.artcam")});
    QCOMPARE(r.exit_code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliCompose)
#include "test_cli_compose.moc"
