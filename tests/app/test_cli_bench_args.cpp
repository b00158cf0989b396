// SPDX-License-Identifier: Apache-2.0
// The benchmarks refuse settings they cannot run as asked (no silent clamping of --reps 0 to 1,
// no library text for a word where a number belongs): exit 2 and one line naming the option.
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

class TestCliBenchArgs : public QObject {
  Q_OBJECT

 private slots:
  void refusedNamingTheOption() {
    const std::pair<QStringList, QString> cases[] = {
        {{"bench", "render", "--reps", "0"}, "--reps expects a whole number"},
        {{"bench", "render", "--threads", "0,1"}, "--threads expects whole numbers"},
        {{"bench", "render", "--type", "uint32"}, "--type expects uint8, uint16 or float"},
        {{"bench", "effects", "--reps", "0"}, "--reps expects a whole number"},
        {{"bench", "effects", "--crop", "x"}, "--crop expects a whole number"},
        {{"bench", "effects", "--threads", "-1"}, "--threads expects a whole number"},
        {{"bench", "effects", "--ratio", "1"}, "--ratio expects a number > 1"},
        {{"bench", "effects", "--shrink-from", "abc"}, "--shrink-from expects a number > 0"},
    };
    for (const auto& [args, says] : cases) {
      const Run r = artcamCli(args);
      const QString what = args.join(' ') + " -> " + r.err;
      QVERIFY2(r.exit_code == 2, qPrintable(what));
      QVERIFY2(r.err.contains(says), qPrintable(what));
      QVERIFY2(!r.err.contains("stoi") && !r.err.contains("stod"), qPrintable(what));
      QVERIFY2(r.out.isEmpty(), qPrintable(what));  // nothing was measured
    }
  }
};

QTEST_GUILESS_MAIN(TestCliBenchArgs)
#include "test_cli_bench_args.moc"
