// SPDX-License-Identifier: Apache-2.0
// Names the user did not type reach a terminal escaped: a file name, a CSV label with ESC, CSI,
// BEL or a carriage return in it is shown as "\x1b[2J", never obeyed. The runs here have a real
// pseudo-terminal as standard output and error (forkpty); a pipe gets the bytes unchanged.
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QTemporaryDir>

#include <pty.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <vector>

using artcam::test::artcamCli;

namespace {

struct TerminalRun {
  int exit_code = -1;
  QByteArray screen;  // what the terminal received, standard output and error together
};

// Runs artcam with both output streams on a raw pseudo-terminal (no newline translation).
TerminalRun runOnTerminal(const QList<QByteArray>& args) {
  TerminalRun run;
  termios raw{};
  ::cfmakeraw(&raw);
  int master = -1;
  const pid_t pid = ::forkpty(&master, nullptr, &raw, nullptr);
  if (pid < 0) return run;
  if (pid == 0) {
    std::vector<char*> argv;
    static char program[] = ARTCAM_CLI_PATH;
    argv.push_back(program);
    for (const QByteArray& a : args) argv.push_back(const_cast<char*>(a.constData()));
    argv.push_back(nullptr);
    ::execv(program, argv.data());
    ::_exit(127);
  }
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(master, buffer, sizeof buffer);
    if (n > 0) {
      run.screen.append(buffer, static_cast<int>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    break;  // EIO once the child has closed the terminal
  }
  ::close(master);
  int status = 0;
  if (::waitpid(pid, &status, 0) == pid && WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

bool writeFile(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}

}  // namespace

class TestCliTerminalText : public QObject {
  Q_OBJECT
 private slots:
  void aFileNameIsShownEscapedOnATerminal() {
    QTemporaryDir dir;
    // A window title, a clear screen and a bell in a missing camera's name.
    const QByteArray name = dir.path().toUtf8() + "/x\x1b]0;owned\x07\x1b[2J\r.artcam";
    const TerminalRun r = runOnTerminal({"info", name});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(!r.screen.contains('\x1b') && !r.screen.contains('\x07') && !r.screen.contains('\r'),
             r.screen.toPercentEncoding().constData());
    QVERIFY2(r.screen.contains("/x\\x1b]0;owned\\x07\\x1b[2J\\r.artcam: cannot read"),
             r.screen.constData());
  }

  void aC1ControlIsEscapedButOtherTextIsNot() {
    QTemporaryDir dir;
    // U+009B is CSI on its own; "é" (C3 A9) and "°" (C2 B0) are ordinary letters.
    const QByteArray name = dir.path().toUtf8() +
                            "/caf\xc3\xa9 \xc2\xb0 \xc2\x9b"
                            "2J.artcam";
    const TerminalRun r = runOnTerminal({"info", name});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(!r.screen.contains("\xc2\x9b"), r.screen.toPercentEncoding().constData());
    QVERIFY2(r.screen.contains("caf\xc3\xa9 \xc2\xb0 \\u009b2J.artcam"), r.screen.constData());
  }

  void aLineLabelIsEscapedInTheReport() {
    QTemporaryDir dir;
    QByteArray csv = "line,x,y\n";
    for (int k = 0; k <= 10; ++k)
      csv += "\x1b[2Jedge," + QByteArray::number(20 + 56 * k) + ",100\n";
    for (int k = 0; k <= 10; ++k) csv += "low," + QByteArray::number(20 + 56 * k) + ",300\n";
    QVERIFY(writeFile(dir.filePath("lines.csv"), csv));
    const QByteArray out = dir.filePath("o.artcam").toUtf8();
    const TerminalRun r = runOnTerminal(
        {"fit", "--lines", dir.filePath("lines.csv").toUtf8(), "-o", out, "--size", "600x400"});
    QCOMPARE(r.exit_code, 0);
    // The progress line still draws itself on a terminal, with its own "\r\033[K"; the only
    // control sequences on the screen are those.
    QVERIFY2(r.screen.contains("\r\x1b[K"), r.screen.toPercentEncoding().constData());
    QByteArray text = r.screen;
    text.replace("\r\x1b[K", "");
    QVERIFY2(!text.contains('\x1b') && !text.contains('\r'), text.toPercentEncoding().constData());
    QVERIFY2(text.contains("line \\x1b[2Jedge: 11 points"), text.constData());
  }

  void aPipeGetsTheBytesUnchanged() {
    // Only a terminal obeys the sequences; a log or `| grep` keeps the name as it is on disk.
    QTemporaryDir dir;
    const QString name = dir.path() + QString::fromUtf8("/x\x1b[2J.artcam");
    const auto r = artcamCli({"info", name});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains(name + ": cannot read"), qPrintable(r.err));
  }
};

QTEST_GUILESS_MAIN(TestCliTerminalText)
#include "test_cli_terminal_text.moc"
