// SPDX-License-Identifier: Apache-2.0
// The benchmarks refuse settings they cannot run as asked (no silent clamping of --reps 0 to 1,
// no library text for a word where a number belongs): exit 2 and one line naming the option;
// and what they run, they report as documented.
#include "tests/app/cli_run.h"

#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest/QtTest>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

class TestCliBenchArgs : public QObject {
  Q_OBJECT

 private slots:
  void refusedNamingTheOption() {
    const std::pair<QStringList, QString> cases[] = {
        {{"bench", "render", "--reps", "0"}, "--reps expects a whole number"},
        {{"bench", "render", "--threads", "0,1"},
         "--threads expects comma-separated whole numbers"},
        {{"bench", "render", "--type", "uint32"}, "--type expects uint8, uint16 or float"},
        {{"bench", "effects", "--reps", "0"}, "--reps expects a whole number"},
        {{"bench", "effects", "--crop", "x"}, "--crop expects a whole number"},
        {{"bench", "effects", "--threads", "-1"}, "--threads expects a whole number"},
        {{"bench", "effects", "--ratio", "1"}, "--ratio expects a number above 1"},
        {{"bench", "effects", "--shrink-from", "abc"}, "--shrink-from expects a number above 0"},
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

  void camerasAreTimedAgainstTheYardstickSideBySide() {
    // Each camera's multiple of the homography is the median of pairs rendered side by side,
    // and says so with the homography's own time in those pairs.
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString cam = dir.filePath("barrel.artcam");
    QCOMPARE(artcamCli({"preset", "barrel", "--size", "192x128", "-o", cam}).exit_code, 0);
    const Run r = artcamCli({"bench", "render", "--cameras", cam, "--size", "192x128", "--reps", "3",
                             "--threads", "1", "--no-e2e"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("suite,homography,bilinear,1,"), qPrintable(r.out));
    QVERIFY2(r.out.contains("suite,barrel,bilinear,1,"), qPrintable(r.out));
    const QRegularExpression paired(R"(suite: barrel\s+1 thr\s+[0-9.]+ ms  x[0-9.]+ homography \(paired; it took [0-9.]+ ms\))");
    QVERIFY2(paired.match(r.err).hasMatch(), qPrintable(r.err));
    QVERIFY2(!r.err.contains(QRegularExpression(R"(suite: homography.*paired)")), qPrintable(r.err));
  }
};

QTEST_GUILESS_MAIN(TestCliBenchArgs)
#include "test_cli_bench_args.moc"
