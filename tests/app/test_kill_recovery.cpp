// SPDX-License-Identifier: Apache-2.0
// Recovery after `artcam warp` is SIGKILLed mid-save: the file being
// replaced stays whole and unchanged, the killed writer's temporary is never taken for an
// input or output, and the next save to that name removes it.
#include "core/io/atomic_file.h"
#include "core/io/image_io.h"
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QProcess>
#include <QTemporaryDir>

using namespace artcam;
using namespace artcam::test;
using Run = artcam::test::CliRun;

namespace {
const QString kCamera = QStringLiteral(ARTCAM_RESOURCES_DIR "/sample.artcam");
}

class TestKillRecovery : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void killedMidSaveKeepsTheOldFile() {
    QVERIFY(dir_.isValid());
    QVERIFY(QDir().mkpath(path("out")));
    QVERIFY(writeNoisePhoto(path("photo.png"), 300, 200));
    const QString target = path("out/result.png");
    QVERIFY(writeNoisePhoto(target, 320, 240));  // the file a new save replaces (--overwrite)
    const QByteArray old_bytes = fileBytes(target);

    // A large output (PNG encoding takes seconds) so the kill lands while it is written.
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH),
            {"warp", path("photo.png"), kCamera, "-o", target, "--size", "6000x4000",
             "--overwrite"});
    QVERIFY(p.waitForStarted());
    QVERIFY(waitUntil(
        [&] { return !hiddenFiles(path("out")).isEmpty() || p.state() == QProcess::NotRunning; }));
    QCOMPARE(p.state(), QProcess::Running);
    p.kill();  // SIGKILL: no handler runs, nothing is cleaned up
    QVERIFY(p.waitForFinished(60000));
    QCOMPARE(p.exitStatus(), QProcess::CrashExit);

    // The old file: byte for byte, and it still decodes completely.
    QCOMPARE(fileBytes(target), old_bytes);
    const auto old_image = readImage(target.toStdString());
    QVERIFY(old_image);
    QCOMPARE(old_image->image.width, 320);
    const QStringList stale = hiddenFiles(path("out"));
    QCOMPARE(stale.size(), 1);
    QVERIFY2(isAtomicTemporaryName(stale.front().toStdString()), qPrintable(stale.front()));
    QCOMPARE(visibleFiles(path("out")), QStringList({"result.png"}));

    // A batch handed the temporary skips it: it is never an input, so never an output either.
    const Run b = artcamCli({"batch", kCamera, path("out/" + stale.front()), "-o", path("batch")});
    QVERIFY2(b.err.contains("skipping") && b.err.contains(stale.front()), qPrintable(b.err));
    QVERIFY(visibleFiles(path("batch")).isEmpty());

    // The next save to that name removes the dead writer's temporary.
    const Run again =
        artcamCli({"warp", path("photo.png"), kCamera, "-o", target, "--overwrite"});
    QVERIFY2(again.exit_code == 0, qPrintable(again.err));
    QVERIFY2(hiddenFiles(path("out")).isEmpty(), qPrintable(hiddenFiles(path("out")).join(", ")));
    const auto fresh = readImage(target.toStdString());
    QVERIFY(fresh);
    QCOMPARE(fresh->image.width, 300);
    QCOMPARE(fresh->image.height, 200);
  }

  // A temporary whose writer is alive (this test process) is left alone.
  void aLiveWritersTemporaryIsKept() {
    QVERIFY(QDir().mkpath(path("live")));
    const QString live =
        path(QStringLiteral("live/.x.tmp-%1-0.png").arg(QCoreApplication::applicationPid()));
    QFile f(live);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.close();
    QCOMPARE(removeStaleTemporaries(path("live/x.png").toStdString()), 0);
    QVERIFY(QFile::exists(live));
  }
};

QTEST_GUILESS_MAIN(TestKillRecovery)
#include "test_kill_recovery.moc"
