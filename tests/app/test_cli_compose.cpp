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
