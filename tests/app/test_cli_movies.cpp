// SPDX-License-Identifier: Apache-2.0
// Movie files are refused in one line before any reader opens them, in every command that reads
// an image, by their bytes as well as by their name; OpenImageIO 2.4's movie reader, which
// aborts the process on ordinary clips, is never reached. The clips are real ones, made by
// ffmpeg (an independent encoder) in each common container; hand-made headers are in the
// hostile corpus (tests/hostile/cases-streams.tsv).
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>

using artcam::test::artcamCli;

class TestCliMovies : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }
  bool have_ffmpeg_ = false;

  // A three-frame 64x48 clip of ffmpeg's test pattern in `name`'s container.
  bool makeClip(const QString& name) const {
    QProcess ff;
    ff.start("ffmpeg", {"-loglevel", "error", "-y", "-f", "lavfi", "-i",
                        "testsrc=size=64x48:rate=5", "-frames:v", "3", path(name)});
    return ff.waitForFinished(60000) && ff.exitCode() == 0;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    have_ffmpeg_ = !QStandardPaths::findExecutable("ffmpeg").isEmpty();
    const auto preset = artcamCli({"preset", "barrel", "--size", "64x48", "-o", path("c.artcam")});
    QVERIFY2(preset.exit_code == 0, qPrintable(preset.err));
  }

  void everyContainerIsRefusedInOneLine_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<QString>("kind");
    QTest::newRow("mp4") << "clip.mp4"
                         << "MP4";
    QTest::newRow("mov") << "clip.mov"
                         << "QuickTime";
    QTest::newRow("avi") << "clip.avi"
                         << "AVI";
    QTest::newRow("mkv") << "clip.mkv"
                         << "Matroska/WebM";
    QTest::newRow("webm") << "clip.webm"
                          << "Matroska/WebM";
  }
  void everyContainerIsRefusedInOneLine() {
    if (!have_ffmpeg_) QFAIL("ffmpeg is not installed: no real clips to make (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QFETCH(QString, name);
    QFETCH(QString, kind);
    QVERIFY2(makeClip(name), qPrintable(name));
    // By its name and, renamed as a still, by its bytes.
    const QString still = path(name + ".png");
    QVERIFY(QFile::copy(path(name), still));
    for (const QString& clip : {path(name), still}) {
      const auto warp = artcamCli({"warp", clip, path("c.artcam"), "-o", path("o.png")});
      QCOMPARE(warp.exit_code, 1);  // exited, not killed by an abort (-1)
      QCOMPARE(warp.err.trimmed().count('\n'), 0);
      QVERIFY2(warp.err.contains(clip + ": cannot read: a movie (" + kind + ")"),
               qPrintable(warp.err));
      QVERIFY(!QFile::exists(path("o.png")));
    }
    const auto batch = artcamCli({"batch", path("c.artcam"), path(name), "-o", path("out")});
    QVERIFY(batch.exit_code > 0);
    QVERIFY2(batch.err.contains("a movie (" + kind + ")"), qPrintable(batch.err));
    const auto info = artcamCli({"info", path(name)});
    QCOMPARE(info.exit_code, 1);
    QVERIFY2(info.err.contains("it looks like a movie (" + kind + ")"), qPrintable(info.err));
  }

  // The stream route reads the same bytes: a clip piped in is refused the same way.
  void aClipThroughStdinIsRefused() {
    if (!have_ffmpeg_) QFAIL("ffmpeg is not installed: no real clips to make (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QVERIFY(makeClip("piped.mp4"));
    QFile clip(path("piped.mp4"));
    QVERIFY(clip.open(QIODevice::ReadOnly));
    const auto run = artcam::test::artcamCliPiped(
        {"warp", "-", path("c.artcam"), "-o", "-", "--format", "png"}, clip.readAll());
    QCOMPARE(run.exit_code, 1);
    QVERIFY(run.out.isEmpty());
    QVERIFY2(run.err.contains("<stdin>: cannot read: a movie (MP4)"), qPrintable(run.err));
  }
};

QTEST_GUILESS_MAIN(TestCliMovies)
#include "test_cli_movies.moc"
