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

}  // namespace artcam::test
