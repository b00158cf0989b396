// SPDX-License-Identifier: Apache-2.0
// Progress and Ctrl-C for the long CLI jobs other than warp and batch (every long CLI
// job shows progress and can be interrupted without leaving partial files): render, insert,
// sample and fit accept --quiet; with stderr not a terminal (a pipe, as here) they write no
// bar, no carriage return and no escape sequence there; SIGINT exits 130 and leaves neither
// the output nor a temporary, both in a stage without a core hook (sample's ray tracing: the
// handler exits at once) and in one that polls (render's image write: the command cancels
// and says so itself).
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFileInfo>
#include <QProcess>
#include <QTemporaryDir>

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

using namespace artcam::test;

namespace {

// Runs the CLI with stderr on a pseudo-terminal (isatty true there) and returns what the
// terminal received; "" with ok = false when no pty could be made.
QByteArray stderrOnTerminal(const QStringList& args, bool& ok) {
  ok = false;
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0) return {};
  QByteArray seen;
  if (::grantpt(master) == 0 && ::unlockpt(master) == 0) {
    if (const char* slave = ::ptsname(master)) {
      QProcess p;
      p.setStandardErrorFile(QString::fromLocal8Bit(slave));
      p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
      ok = p.waitForFinished(300000) && p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0;
      // The child has exited, so its writes are all in the pty's buffer; read without waiting.
      ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
      char buffer[4096];
      for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;)
        seen.append(buffer, static_cast<qsizetype>(n));
    }
  }
  ::close(master);
  return seen;
}

}  // namespace

class TestCliProgress : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // A finished job's stderr as a pipe sees it: empty (no bar is drawn off a terminal, and
  // these commands report on stdout).
  static void verifyQuietStderr(const CliRun& r, const QString& what) {
    QVERIFY2(r.exit_code == 0,
             qPrintable(what + " exited " + QString::number(r.exit_code) + ":\n" + r.err));
    QVERIFY2(!r.err.contains('\r'), qPrintable(what + " wrote a carriage return: " + r.err));
    QVERIFY2(!r.err.contains(QChar(0x1b)), qPrintable(what + " wrote an escape: " + r.err));
    QVERIFY2(r.err.isEmpty(), qPrintable(what + " wrote on stderr: " + r.err));
    QVERIFY2(!r.out.isEmpty(), qPrintable(what + " printed no report"));
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QCOMPARE(artcamCli({"preset", "twist-3d", "-o", path("twist.artcam")}).exit_code, 0);
  }

  // Each command once plainly and once with --quiet (and -q): both succeed with the same
  // outputs and nothing on stderr.
  void noBarOffATerminalAndQuietAccepted() {
    for (const QString& quiet : {QString(), QStringLiteral("--quiet"), QStringLiteral("-q")}) {
      const QString tag = quiet.isEmpty() ? QStringLiteral("plain") : QString(quiet).remove('-');
      const QString out = path(tag);
      QVERIFY(QDir().mkpath(out));
      auto with = [&](QStringList args) {
        if (!quiet.isEmpty()) args << quiet;
        return args;
      };
      const QString sample = out + "/sample";
      verifyQuietStderr(artcamCli(with({"sample", "mirror-sphere", "-o", sample, "--size",
                                        "320x240", "--squares", "8"})),
                        "sample " + tag);
      const QString photo = sample + "/mirror-sphere.png";
      const QString grid = sample + "/mirror-sphere-grid.csv";
      for (const QString& f : {photo, grid, sample + "/emblem.png"})
        QVERIFY2(QFileInfo::exists(f), qPrintable(f));

      verifyQuietStderr(
          artcamCli(with({"render", QStringLiteral(ARTCAM_RESOURCES_DIR "/cube.ply"),
                          path("twist.artcam"), "-o", out + "/cube.png", "--size", "200x150"})),
          "render " + tag);
      verifyQuietStderr(artcamCli(with({"render", QStringLiteral(ARTCAM_RESOURCES_DIR "/cube.ply"),
                                        path("twist.artcam"), "-o", out + "/cube.ply"})),
                        "render to PLY " + tag);
      verifyQuietStderr(artcamCli(with({"insert", photo, sample + "/emblem.png", "--matches", grid,
                                        "-o", out + "/inserted.png"})),
                        "insert " + tag);
      verifyQuietStderr(artcamCli(with({"fit", grid, "--size", "512x512", "--target-size",
                                        "320x240", "--robust", "-o", out + "/robust.artcam"})),
                        "fit --robust " + tag);
      verifyQuietStderr(artcamCli(with({"fit", grid, "--size", "512x512", "--target-size",
                                        "320x240", "--piecewise", "-o", out + "/pieces.artcam"})),
                        "fit --piecewise " + tag);
      for (const char* f :
           {"cube.png", "cube.ply", "inserted.png", "robust.artcam", "pieces.artcam"})
        QVERIFY2(QFileInfo(out + '/' + f).size() > 0, f);
      QVERIFY(hiddenFiles(out).isEmpty());
      QVERIFY(hiddenFiles(sample).isEmpty());
    }
  }

  // On a terminal the bar is drawn in place (carriage return + erase line) naming the stages,
  // and cleared before the report; --quiet draws nothing.
  void barOnATerminalUnlessQuiet() {
    const QStringList render = {"render",
                                QStringLiteral(ARTCAM_RESOURCES_DIR "/cube.ply"),
                                path("twist.artcam"),
                                "-o",
                                path("terminal.png"),
                                "--size",
                                "600x400",
                                "--overwrite"};  // run twice below
    bool ok = false;
    const QByteArray bar = stderrOnTerminal(render, ok);
    QVERIFY(ok);
    QVERIFY2(bar.contains("\r\033[K"), bar.constData());
    for (const char* stage : {"reading", "rendering", "writing"})
      QVERIFY2(bar.contains(stage), bar.constData());
    QVERIFY2(bar.endsWith("\r\033[K"), bar.constData());  // cleared at the end
    const QByteArray quiet = stderrOnTerminal(QStringList(render) << "--quiet", ok);
    QVERIFY(ok);
    QVERIFY2(quiet.isEmpty(), quiet.constData());
  }

  // Ray tracing has no progress hook in core: SIGINT there exits at once with 130, and the
  // folder (created before the trace starts) stays empty. 4000x3000 traces for many seconds;
  // the signal goes as soon as the folder exists.
  void sampleInterruptedWhileTracingLeavesNothing() {
    const QString folder = path("traced");
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH),
            {"sample", "water-glass", "-o", folder, "--size", "4000x3000"});
    QVERIFY(p.waitForStarted());
    QVERIFY(
        waitUntil([&] { return QFileInfo(folder).isDir() || p.state() == QProcess::NotRunning; }));
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGINT), 0);
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 130);
    const QStringList left = QDir(folder).entryList(QDir::Files | QDir::Hidden | QDir::System);
    QVERIFY2(left.isEmpty(), qPrintable(left.join(", ")));
  }

  // The image write polls: SIGINT while render's temporary exists cancels the write (the atomic
  // writer removes the temporary), and the command itself reports it and exits 130.
  void renderInterruptedWhileWritingCancelsCooperatively() {
    const QString folder = path("rendered");
    QVERIFY(QDir().mkpath(folder));
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH),
            {"render", QStringLiteral(ARTCAM_RESOURCES_DIR "/cube.ply"), path("twist.artcam"), "-o",
             folder + "/big.png", "--size", "6000x6000"});
    QVERIFY(p.waitForStarted());
    QVERIFY(waitUntil(
        [&] { return !hiddenFiles(folder).isEmpty() || p.state() == QProcess::NotRunning; }));
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGINT), 0);
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 130);
    const QString err = QString::fromUtf8(p.readAllStandardError());
    // The cooperative path's own line, not the signal handler's "artcam: interrupted".
    QVERIFY2(err.contains("artcam render: interrupted"), qPrintable(err));
    QVERIFY2(!err.contains('\r'), qPrintable(err));
    const QStringList left = QDir(folder).entryList(QDir::Files | QDir::Hidden | QDir::System);
    QVERIFY2(left.isEmpty(), qPrintable(left.join(", ")));
  }
};

QTEST_GUILESS_MAIN(TestCliProgress)
#include "test_cli_progress.moc"
