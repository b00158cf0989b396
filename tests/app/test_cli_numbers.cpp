// SPDX-License-Identifier: Apache-2.0
// Numbers on the command line have one spelling (app/cli/args.h, parseInteger/parseNumber): the
// whole text is the number, finite and within the option's range. Anything else is a usage
// error: exit 2, nothing on stdout, nothing written, and a first line that names the option,
// the range it takes and the text given, in the CLI's words (never "stoi" or "stoul").
// The expected lines are the ranges the help pages and artcam(1) document, written out here by
// hand; `2x` once ran with 2 threads, `1e3` as frame 1, `1px` as 1 px.
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QTemporaryDir>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

const QString kResources = QStringLiteral(ARTCAM_RESOURCES_DIR);

QStringList errorLines(const Run& r) { return r.err.split('\n', Qt::SkipEmptyParts); }

}  // namespace

class TestCliNumbers : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // A refusal as the dialect has it: exit 2, the line `expected` first, then only
  // "see 'artcam CMD --help'", stdout empty, and `output` (if any) not written.
  void expectRefused(const QStringList& args, const QString& expected, const QString& output = {}) {
    const Run r = artcamCli(args);
    const QString call = "artcam " + args.join(' ') + ":\n" + r.err;
    QVERIFY2(r.exit_code == 2, qPrintable(call));
    QVERIFY2(r.out.isEmpty(), qPrintable(call + "\nstdout: " + r.out));
    const QStringList lines = errorLines(r);
    QVERIFY2(lines.size() == 2, qPrintable(call));
    QVERIFY2(lines[0] == expected, qPrintable(call + "\nexpected: " + expected));
    QVERIFY2(lines[1].startsWith("see 'artcam "), qPrintable(call));
    for (const char* library : {"stoi", "stol", "stoul", "stod", "stof", "std::"})
      QVERIFY2(!r.err.contains(library), qPrintable(call));
    if (!output.isEmpty()) QVERIFY2(!QFile::exists(output), qPrintable(call));
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(QFile::copy(kResources + "/coffee.png", path("photo.png")));
    QVERIFY(QFile::copy(kResources + "/sample.artcam", path("cam.artcam")));
    QVERIFY(QFile::copy(kResources + "/sample-matches.csv", path("m.csv")));
    QVERIFY(QDir().mkpath(path("seq")));
    QVERIFY(artcam::test::writeNoisePhoto(path("seq/f_0001.png"), 60, 40));
    QVERIFY(artcam::test::writeNoisePhoto(path("photo.jpg"), 60, 40));
  }

  // Whole numbers: trailing text, a sign out of range, exponents and overflow are refused.
  void wholeNumbersAreWhole() {
    const QStringList warp = {"warp", path("photo.png"), path("cam.artcam"), "-o", path("w.png")};
    for (const char* text : {"2x", "-1", "1025", "1.5", "1e3", " 2", "+2", "99999999999999999999"})
      expectRefused(QStringList(warp) << "--threads" << text,
                    QStringLiteral("artcam warp: --threads expects a whole number from 0 to 1024, "
                                   "got \"%1\"")
                        .arg(text),
                    path("w.png"));
    expectRefused(
        {"warp", path("photo.jpg"), path("cam.artcam"), "-o", path("q.jpg"), "--quality", "90q"},
        "artcam warp: --quality expects a whole number from 1 to 100, got \"90q\"", path("q.jpg"));
    expectRefused(
        {"batch", path("cam.artcam"), path("seq/f_%04d.png"), "-o", path("b"), "--first", "1e3"},
        "artcam batch: --first expects a whole number from -1000000000 to 1000000000, "
        "got \"1e3\"");
    expectRefused(
        {"batch", path("cam.artcam"), path("photo.png"), "-o", path("b"), "--threads", "4 "},
        "artcam batch: --threads expects a whole number from 0 to 1024, got \"4 \"");
    expectRefused(
        {"render", path("c.ply"), path("cam.artcam"), "-o", path("r.png"), "--threads", "2x"},
        "artcam render: --threads expects a whole number from 0 to 1024, got \"2x\"");
    expectRefused({"sample", "water-glass", "-o", path("s"), "--squares", "8x"},
                  "artcam sample: --squares expects a whole number from 2 to 256, got \"8x\"");
    expectRefused({"lens", "search", "canon", "--limit", "5x"},
                  "artcam lens: --limit expects a whole number from 0 to 1000000, got \"5x\"");
    expectRefused({"bench", "render", "--size", "64x48", "--no-e2e", "--reps", "3x"},
                  "artcam bench: --reps expects a whole number from 1 to 1000, got \"3x\"");
    expectRefused({"bench", "render", "--size", "64x48", "--no-e2e", "--threads", "1,2x"},
                  "artcam bench: --threads expects comma-separated whole numbers from 1 to 1024, "
                  "got \"1,2x\"");
    expectRefused({"bench", "fit", "--counts", "9,1e3"},
                  "artcam bench: --counts expects comma-separated whole numbers from 9 to "
                  "1000000, got \"9,1e3\"");
    expectRefused({"bench", "effects", "--crop", "64px"},
                  "artcam bench: --crop expects a whole number from 8 to 1000000, got \"64px\"");
  }

  // Numbers: trailing units, non-finite values and values past an open end are refused.
  void numbersAreNumbers() {
    const QStringList piecewise = {"fit",    path("m.csv"), "-o",          path("p.artcam"),
                                   "--size", "600x400",     "--piecewise", "--max-error"};
    for (const char* text : {"1px", "0", "-0.5", "nan", "inf", "1e999"})
      expectRefused(
          QStringList(piecewise) << text,
          QStringLiteral("artcam fit: --max-error expects a number above 0, got \"%1\"").arg(text),
          path("p.artcam"));
    expectRefused({"fit", path("m.csv"), "-o", path("t.artcam"), "--size", "600x400", "--robust",
                   "--threshold", "3px"},
                  "artcam fit: --threshold expects a number above 0, got \"3px\"",
                  path("t.artcam"));
    expectRefused(
        {"warp", path("photo.png"), path("cam.artcam"), "-o", path("d.png"), "--depth-scale", "1m"},
        "artcam warp: --depth-scale expects a number above 0, got \"1m\"", path("d.png"));
    expectRefused(
        {"render", path("c.ply"), path("cam.artcam"), "-o", path("r.png"), "--fov", "180"},
        "artcam render: --fov expects a number above 0, below 180, got \"180\"");
    expectRefused({"insert", path("photo.png"), path("photo.png"), "--matches", path("m.csv"), "-o",
                   path("i.png"), "--mesh-step", "2px"},
                  "artcam insert: --mesh-step expects a number above 0, got \"2px\"",
                  path("i.png"));
    expectRefused({"bench", "fit", "--seconds", "0.3s"},
                  "artcam bench: --seconds expects a number above 0, at most 3600, got \"0.3s\"");
    expectRefused({"bench", "fit", "--noise", "0,-1"},
                  "artcam bench: --noise expects comma-separated numbers of at least 0, got "
                  "\"0,-1\"");
    expectRefused({"preset", "barrel", "--k", "0.1x", "-o", path("k.artcam")},
                  "artcam preset: --k expects comma-separated numbers, got \"0.1x\"",
                  path("k.artcam"));
  }

  // A frame pattern's zero padding is bounded: %0Nd with N up to 32, refused beyond in the
  // CLI's words (std::stoul once leaked "stoul" for the width below).
  void framePaddingIsBounded() {
    for (const char* digits : {"099999999999999999999", "033"}) {
      const QString width = QString::fromLatin1(digits);
      const QString pattern = path("seq/f_%" + width + "d.png");
      expectRefused({"batch", path("cam.artcam"), pattern, "-o", path("b")},
                    "artcam batch: \"" + pattern +
                        "\": a frame pattern pads to at most 32 digits (%032d), got %" + width +
                        "d");
    }
    const Run padded = artcamCli(
        {"batch", path("cam.artcam"), path("seq/f_%04d.png"), "-o", path("b32"), "--quiet"});
    QVERIFY2(padded.exit_code == 0, qPrintable(padded.err));
  }

  // What the ranges admit still runs.
  void numbersInRangeRun() {
    const Run r = artcamCli({"warp", path("photo.jpg"), path("cam.artcam"), "-o", path("ok.jpg"),
                             "--threads", "1", "--quality", "100", "--quiet"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Run first = artcamCli({"batch", path("cam.artcam"), path("seq/f_%04d.png"), "-o",
                                 path("first"), "--first", "1", "--threads=0", "--quiet"});
    QVERIFY2(first.exit_code == 0, qPrintable(first.err));
    QVERIFY(QFile::exists(path("first/f_0001.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliNumbers)
#include "test_cli_numbers.moc"
