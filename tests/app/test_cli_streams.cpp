// SPDX-License-Identifier: Apache-2.0
// "-" for every single-file argument besides warp's photo (test_cli_stdio.cpp): cameras,
// matches, points and maps read from standard input, cameras and maps written to standard
// output, with the reports on stderr so a pipe gets the file alone; "-" refused in one line
// where it names a folder or where two arguments would share one stream. The truths: the same
// command over named files (byte for byte), jq (an independent JSON parser) and oiiotool's
// iinfo for the map.
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>

using artcam::test::artcamCli;
using artcam::test::artcamCliPiped;
using artcam::test::fileBytes;
using Piped = artcam::test::CliBytesRun;

namespace {

bool writeBytes(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}

// Exact matches of a translation by (1, 2): the fit is that translation whatever reads it.
const QByteArray kMatches =
    "src_x,src_y,dst_x,dst_y\n0,0,1,2\n100,0,101,2\n0,100,1,102\n100,100,101,102\n"
    "50,50,51,52\n20,70,21,72\n";

}  // namespace

class TestCliStreams : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }
  // The entries of the test folder: a run must never leave a file named "-".
  bool dashFileMade() const { return QFileInfo::exists(path("-")); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeBytes(path("m.csv"), kMatches));
    const auto fit = artcamCli({"fit", path("m.csv"), "--size", "100x100", "-o", path("c.artcam")});
    QVERIFY2(fit.exit_code == 0, qPrintable(fit.err));
  }

  // The promise of the manual: `artcam fit … -o - | jq .` works, through a real shell pipe.
  void fitToStdoutPipesIntoJq() {
    if (QStandardPaths::findExecutable("jq").isEmpty()) QFAIL("jq is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QProcess sh;
    sh.setWorkingDirectory(dir_.path());
    sh.start("bash", {"-o", "pipefail", "-c",
                      QStringLiteral("'%1' fit m.csv --size 100x100 -o - | jq -c '.frames.source'")
                          .arg(ARTCAM_CLI_PATH)});
    QVERIFY(sh.waitForFinished(60000));
    const QString err = QString::fromUtf8(sh.readAllStandardError());
    QVERIFY2(sh.exitCode() == 0, qPrintable(err));
    QCOMPARE(QString::fromUtf8(sh.readAllStandardOutput()).trimmed(), QStringLiteral("[100,100]"));
    // The fit's report went to the terminal, naming the stream.
    QVERIFY2(err.contains("wrote <stdout>"), qPrintable(err));
    QVERIFY(!dashFileMade());
  }

  // Each text output "-" carries exactly the file the named output gets.
  void textOutputsEqualTheFileRoute() {
    const QList<QStringList> commands = {
        {"fit", path("m.csv"), "--size", "100x100"},
        {"preset", "barrel", "--size", "100x100"},
        {"compose", path("c.artcam"), path("c.artcam")},
    };
    for (const QStringList& command : commands) {
      const QString file = path("route-" + command[0] + ".artcam");
      const auto named = artcamCli(command + QStringList{"-o", file});
      const Piped piped = artcamCliPiped(command + QStringList{"-o", "-"}, {});
      QCOMPARE(piped.exit_code, named.exit_code);
      if (named.exit_code != 0) {
        QVERIFY(piped.out.isEmpty());
        continue;
      }
      QCOMPARE(piped.out, fileBytes(file));
      QVERIFY2(piped.err.contains("wrote <stdout>"), qPrintable(piped.err));
    }
    QVERIFY(!dashFileMade());
  }

  // Cameras, matches and points from standard input give what the named files give.
  void textInputsEqualTheFileRoute() {
    const QByteArray camera = fileBytes(path("c.artcam"));
    const auto fit_named =
        artcamCli({"fit", path("m.csv"), "--size", "100x100", "-o", path("f1.artcam")});
    const Piped fit_piped =
        artcamCliPiped({"fit", "-", "--size", "100x100", "-o", path("f2.artcam")}, kMatches);
    QVERIFY2(fit_piped.exit_code == 0, qPrintable(fit_piped.err));
    QCOMPARE(fit_named.exit_code, 0);
    QCOMPARE(fileBytes(path("f2.artcam")), fileBytes(path("f1.artcam")));

    QVERIFY(writeBytes(path("p.csv"), "x,y\n10,10\n0.5,99\n"));
    const auto map_named = artcamCli({"map", path("c.artcam"), path("p.csv")});
    const Piped map_camera = artcamCliPiped({"map", "-", path("p.csv")}, camera);
    const Piped map_points = artcamCliPiped({"map", path("c.artcam"), "-"}, "x,y\n10,10\n0.5,99\n");
    QCOMPARE(map_named.exit_code, 0);
    QCOMPARE(map_camera.exit_code, 0);
    QCOMPARE(map_points.exit_code, 0);
    // The translation by (1, 2): independent of any reader.
    QCOMPARE(map_named.out, QStringLiteral("10,10,11,12\n0.5,99,1.5,101\n"));
    QCOMPARE(QString::fromUtf8(map_camera.out), map_named.out);
    QCOMPARE(QString::fromUtf8(map_points.out), map_named.out);

    const Piped info = artcamCliPiped({"info", "-", "--json"}, camera);
    QVERIFY2(info.exit_code == 0, qPrintable(info.err));
    QVERIFY2(info.out.contains("\"file\":\"<stdin>\""), info.out.constData());
  }

  // An ST map through both streams: export-map -o - is the EXR the named output is, and
  // fit --stmap - reads it back to the same camera.
  void mapsThroughTheStreams() {
    const auto named = artcamCli(
        {"export-map", path("c.artcam"), "--size", "64x64", "-o", path("map.exr"), "--overwrite"});
    QVERIFY2(named.exit_code == 0, qPrintable(named.err));
    const Piped piped =
        artcamCliPiped({"export-map", path("c.artcam"), "--size", "64x64", "-o", "-"}, {});
    QVERIFY2(piped.exit_code == 0, qPrintable(piped.err));
    QVERIFY(writeBytes(path("piped-map.exr"), piped.out));
    if (!QStandardPaths::findExecutable("idiff").isEmpty()) {
      QProcess idiff;
      idiff.start("idiff", {"-a", path("map.exr"), path("piped-map.exr")});
      QVERIFY(idiff.waitForFinished(60000));
      QVERIFY2(idiff.exitCode() == 0, idiff.readAllStandardOutput().constData());
    }
    const auto fit_named = artcamCli({"fit", "--stmap", path("map.exr"), "-o", path("s1.artcam")});
    const Piped fit_piped = artcamCliPiped({"fit", "--stmap", "-", "-o", path("s2.artcam")},
                                           fileBytes(path("map.exr")));
    QVERIFY2(fit_named.exit_code == 0, qPrintable(fit_named.err));
    QVERIFY2(fit_piped.exit_code == 0, qPrintable(fit_piped.err));
    QVERIFY2(fit_piped.out.startsWith("<stdin>: "), fit_piped.out.constData());
    QCOMPARE(fileBytes(path("s2.artcam")), fileBytes(path("s1.artcam")));
  }

  // Where "-" cannot mean one stream it is refused in one line, exit 2, and nothing is made.
  void refusedWhereItCannotMeanOneStream() {
    struct Case {
      QStringList args;
      QString says;
    };
    const QList<Case> cases = {
        {{"batch", path("c.artcam"), path("m.csv"), "-o", "-"}, "names a folder"},
        {{"sample", "mirror-sphere", "-o", "-"}, "names a folder"},
        {{"batch", path("c.artcam"), "-", "-o", path("d")}, "by name"},
        {{"map", "-", "-"}, "two inputs are \"-\""},
        {{"compose", "-", "-", "-o", path("x.artcam")}, "two inputs are \"-\""},
        {{"warp", "-", "-", "-o", path("x.png")}, "two inputs are \"-\""},
        {{"fit", "-", "--size", "100x100", "-o", "-", "--json"}, "--json"},
    };
    for (const Case& c : cases) {
      const Piped run = artcamCliPiped(c.args, kMatches);
      QVERIFY2(run.exit_code == 2, qPrintable(c.args.join(' ') + ": " + run.err));
      QVERIFY2(run.err.contains(c.says), qPrintable(run.err));
      QVERIFY2(run.err.trimmed().split('\n').size() <= 2, qPrintable(run.err));  // + "see …"
      QVERIFY(run.out.isEmpty());
    }
    QVERIFY(!dashFileMade());
    QVERIFY(!QFileInfo::exists(path("x.artcam")));
    QVERIFY(!QFileInfo::exists(path("d")));
  }
};

QTEST_GUILESS_MAIN(TestCliStreams)
#include "test_cli_streams.moc"
