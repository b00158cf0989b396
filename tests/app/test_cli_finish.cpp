// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 5 end to end: nine points drawn on a photo, the camera fitted to them, the warp
// rendered with pencil marks (artcam warp --finish); the same commands give the same bytes.
#include "tests/app/cli_run.h"

#include <QTemporaryDir>
#include <QtTest/QtTest>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

class TestCliFinish : public QObject {
  Q_OBJECT

 private slots:
  void nineSourceTargetPointsThenMarks() {
    QTemporaryDir dir;
    // A 3 × 3 grid over the 600 × 400 photo, its centre pulled up and right, the rest held.
    QFile csv(dir.filePath("nine.csv"));
    QVERIFY(csv.open(QIODevice::WriteOnly));
    csv.write("src_x,src_y,dst_x,dst_y\n");
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const double x = 50 + 250 * i, y = 50 + 150 * j;
        const bool centre = i == 1 && j == 1;
        csv.write(QString("%1,%2,%3,%4\n")
                      .arg(x)
                      .arg(y)
                      .arg(centre ? x + 40 : x)
                      .arg(centre ? y - 30 : y)
                      .toUtf8());
      }
    csv.close();
    Run r = artcamCli(
        {"fit", dir.filePath("nine.csv"), "--size", "600x400", "-o", dir.filePath("fig5.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QString photo = QStringLiteral(ARTCAM_SOURCE_DIR "/resources/coffee.png");
    for (const char* out : {"a.png", "b.png"}) {
      r = artcamCli({"warp", photo, dir.filePath("fig5.artcam"), "-o", dir.filePath(out),
                     "--finish", "pencil"});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    }
    r = artcamCli({"warp", photo, dir.filePath("fig5.artcam"), "-o", dir.filePath("plain.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QFile a(dir.filePath("a.png")), b(dir.filePath("b.png")), plain(dir.filePath("plain.png"));
    QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly) &&
            plain.open(QIODevice::ReadOnly));
    const QByteArray marked = a.readAll();
    QVERIFY(marked == b.readAll());      // reproducible end to end
    QVERIFY(marked != plain.readAll());  // and marked
    // JPEG output and the linear-light path (a float EXR) take the finish too.
    r = artcamCli({"warp", photo, dir.filePath("fig5.artcam"), "-o", dir.filePath("m.exr"),
                   "--finish", "painting"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
  }

  void unknownFinishIsAUsageError() {
    QTemporaryDir dir;
    const QString photo = QStringLiteral(ARTCAM_SOURCE_DIR "/resources/coffee.png");
    const Run r =
        artcamCli({"warp", photo, QStringLiteral(ARTCAM_SOURCE_DIR "/resources/sample.artcam"),
                   "-o", dir.filePath("x.png"), "--finish", "pencl"});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("unknown --finish") && r.err.contains("pencil"), qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("x.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliFinish)
#include "test_cli_finish.moc"
