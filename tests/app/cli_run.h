// SPDX-License-Identifier: Apache-2.0
// Running the public `artcam` CLI as a process from the app tests (ARTCAM_CLI_PATH is defined
// for every test under tests/app/).
#pragma once

#include <QProcess>
#include <QString>
#include <QStringList>

namespace artcam::test {

struct CliRun {
  int exit_code = -1;  // -1: crashed or timed out
  QString out;
  QString err;
};

inline CliRun artcamCli(const QStringList& args, int timeout_ms = 300000) {
  QProcess p;
  p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
  p.waitForFinished(timeout_ms);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
          QString::fromUtf8(p.readAllStandardOutput()), QString::fromUtf8(p.readAllStandardError())};
}

// A run that feeds `input` to standard input and keeps standard output as bytes (an image sent
// to stdout by `-o -`). `environment` entries ("NAME=value") are added to the test's own.
struct CliBytesRun {
  int exit_code = -1;  // -1: crashed or timed out
  QByteArray out;
  QString err;
};

inline CliBytesRun artcamCliPiped(const QStringList& args, const QByteArray& input,
                                  const QStringList& environment = {}, int timeout_ms = 300000) {
  QProcess p;
  if (!environment.isEmpty()) {
    QStringList env = QProcess::systemEnvironment();
    env += environment;
    p.setEnvironment(env);
  }
  p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
  p.waitForStarted(timeout_ms);
  p.write(input);
  p.closeWriteChannel();
  p.waitForFinished(timeout_ms);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(),
          QString::fromUtf8(p.readAllStandardError())};
}

}  // namespace artcam::test
