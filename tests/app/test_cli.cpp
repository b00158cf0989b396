// SPDX-License-Identifier: Apache-2.0
// The public CLI, run as a process: outputs, exit codes, one-line errors, no partial files.
#include "core/fit/fit_image.h"
#include "core/io/artcam_file.h"
#include "core/model/frames.h"
#include "tests/app/cli_run.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cstdio>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

const FrameSize kFrame{600, 400};

// Nine well-spread matches through a random rational camera, as CSV text.
QByteArray exactMatchesCsv(const Camera& truth, int count) {
  QByteArray csv = "src_x,src_y,dst_x,dst_y\n";
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d s(60.0 + 240.0 * (k % 3) + test::uniform(-20, 20),
                            50.0 + 150.0 * (k / 3 % 3) + test::uniform(-20, 20) + 10.0 * (k / 9));
    const Eigen::Vector2d t = *targetPixelFromSourcePixel(truth, s);
    char line[200];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", s.x(), s.y(), t.x(), t.y());
    csv += line;
  }
  return csv;
}

void writeFile(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write(bytes);
}

}  // namespace

class TestCli : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(QString::fromUtf8(name)); }

 private slots:
  void helpListsEveryCommand() {
    const Run r = artcamCli({"--help"});
    QCOMPARE(r.exit_code, 0);
    for (const char* c : {"fit", "map", "warp", "info", "bench", "render", "preset", "compose",
                          "insert", "sample"})
      QVERIFY2(r.out.contains(QString::fromUtf8(c)), c);
    const Run sub = artcamCli({"fit", "--help"});
    QCOMPARE(sub.exit_code, 0);
    QVERIFY(sub.out.contains("--model"));
    QVERIFY(sub.out.contains("--piecewise"));
    const Run effects = artcamCli({"bench", "effects", "--help"});
    QCOMPARE(effects.exit_code, 0);
    QVERIFY2(effects.out.contains("--sigmas"), qPrintable(effects.out));
  }

  void fitNineExactMatchesReproducesThem() {
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.15);
    writeFile(path("nine.csv"), exactMatchesCsv(truth, 9));
    const Run r = artcamCli({"fit", path("nine.csv"), "-o", path("nine.artcam"), "--size",
                             "600x400", "--model", "quadratic", "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["model"].toString(), QString("quadratic"));
    QCOMPARE(j["matches"].toInt(), 9);
    QVERIFY2(j["max_px"].toDouble() < 1e-9, qPrintable(r.out));
    QVERIFY(j["rms_px"].toDouble() <= j["max_px"].toDouble());
    QVERIFY(QFile::exists(path("nine.artcam")));
  }

  void eightMatchesAreRefusedAndLeaveNoFile() {
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.15);
    writeFile(path("eight.csv"), exactMatchesCsv(truth, 8));
    const Run r = artcamCli({"fit", path("eight.csv"), "-o", path("eight.artcam"), "--size",
                             "600x400", "--model", "quadratic"});
    QVERIFY(r.exit_code != 0);
    QCOMPARE(r.err.count('\n'), 1);  // one line
    QVERIFY2(r.err.contains("eight.csv") && r.err.contains("needs at least 9"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("eight.artcam")));
  }

  // A camera saved and reloaded maps points bit-identically: the CLI's map of the saved file
  // equals the in-process evaluation of the same fit, printed with %.17g.
  void mapOfSavedCameraIsBitIdentical() {
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.15);
    const QByteArray csv = exactMatchesCsv(truth, 12);
    writeFile(path("m.csv"), csv);
    QCOMPARE(artcamCli({"fit", path("m.csv"), "-o", path("m.artcam"), "--size", "600x400",
                        "--model", "quadratic"}).exit_code, 0);
    std::vector<PointMatch> matches;
    for (const QByteArray& line : csv.split('\n').mid(1)) {
      const QList<QByteArray> f = line.split(',');
      if (f.size() != 4) continue;
      matches.push_back({Eigen::Vector2d(f[0].toDouble(), f[1].toDouble()),
                         Eigen::Vector2d(f[2].toDouble(), f[3].toDouble()), true});
    }
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary fit = fitImageCamera(matches, kFrame, kFrame, o);
    QVERIFY(fit.status.ok);
    QByteArray points = "x,y\n";
    QString expected;
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector2d p(test::uniform(0, 600), test::uniform(0, 400));
      char line[200];
      std::snprintf(line, sizeof line, "%.17g,%.17g\n", p.x(), p.y());
      points += line;
      const Eigen::Vector2d pr(QByteArray(line).split(',')[0].toDouble(),
                               QByteArray(line).split(',')[1].trimmed().toDouble());
      const Eigen::Vector2d y = *targetPixelFromSourcePixel(fit.camera, pr);
      std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", pr.x(), pr.y(), y.x(), y.y());
      expected += QString::fromUtf8(line);
    }
    writeFile(path("points.csv"), points);
    const Run r = artcamCli({"map", path("m.artcam"), path("points.csv")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QCOMPARE(r.out, expected);
  }

  void infoDescribesTheCamera() {
    const Camera truth = test::randomHomographyCamera(kFrame, kFrame);
    writeFile(path("h.csv"), exactMatchesCsv(truth, 9));
    QCOMPARE(artcamCli({"fit", path("h.csv"), "-o", path("h.artcam"), "--size", "600x400",
                        "--model", "homography"}).exit_code, 0);
    const Run r = artcamCli({"info", path("h.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("geometry homography"), qPrintable(r.out));
    QVERIFY(r.out.contains("source 600x400"));
    QVERIFY(r.out.contains("fit:       homography, 9 matches"));
  }

  void warpWritesAnImageAndStats() {
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.05);
    writeFile(path("w.csv"), exactMatchesCsv(truth, 12));
    QCOMPARE(artcamCli({"fit", path("w.csv"), "-o", path("w.artcam"), "--size", "600x400"}).exit_code, 0);
    const Run r = artcamCli({"warp", QString::fromStdString(test::resourcePath("coffee.png")),
                             path("w.artcam"), "-o", path("w.png"), "--stats"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains(QRegularExpression("render_ms=[0-9.]+ mpix_per_s=[0-9.]+")), qPrintable(r.err));
    QVERIFY(QFile::exists(path("w.png")));
  }

  void errorsNameFilePlaceAndCause() {
    writeFile(path("bad.csv"), "src_x,src_y,dst_x,dst_y\n1,2,3,4\n5,6,7\n");
    Run r = artcamCli({"fit", path("bad.csv"), "-o", path("bad.artcam"), "--size", "600x400"});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("bad.csv:3"), qPrintable(r.err));
    QCOMPARE(r.err.count('\n'), 1);
    QVERIFY(!QFile::exists(path("bad.artcam")));

    r = artcamCli({"info", path("missing.artcam")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("missing.artcam"), qPrintable(r.err));

    writeFile(path("broken.artcam"), "{\"format\": \"artcam\", \"version\": 1, \"blocks\": 3}");
    r = artcamCli({"info", path("broken.artcam")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("broken.artcam") && r.err.contains("/blocks"), qPrintable(r.err));

    // A warp whose output cannot be written leaves nothing behind.
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.05);
    writeFile(path("e.csv"), exactMatchesCsv(truth, 12));
    QCOMPARE(artcamCli({"fit", path("e.csv"), "-o", path("e.artcam"), "--size", "600x400"}).exit_code, 0);
    r = artcamCli({"warp", path("nonexistent.png"), path("e.artcam"), "-o", path("out.png")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("nonexistent.png"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("out.png")));
    r = artcamCli({"warp", QString::fromStdString(test::resourcePath("coffee.png")), path("e.artcam"),
                   "-o", path("out.unknownext")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("out.unknownext"), qPrintable(r.err));
    QCOMPARE(QDir(dir_.path()).entryList({"*out*"}, QDir::Files | QDir::Hidden).size(), 0);
  }

  // Object space: a preset camera applied to the bundled cloud, to an image and to a cloud.
  void presetAndRenderTheSampleCloud() {
    Run r = artcamCli({"preset", "twist-3d", "-o", path("twist.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"render", QString::fromStdString(test::resourcePath("cube.ply")), path("twist.artcam"),
                   "-o", path("twist.png"), "--size", "128x96"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(QFile::exists(path("twist.png")));
    r = artcamCli({"render", QString::fromStdString(test::resourcePath("cube.ply")), path("twist.artcam"),
                   "-o", path("twisted.ply")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(QFileInfo(path("twisted.ply")).size() > 1000);
    writeFile(path("bad.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n");
    r = artcamCli({"render", path("bad.ply"), path("twist.artcam"), "-o", path("bad.png")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("bad.ply"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("bad.png")));
    QVERIFY(artcamCli({"preset", "no-such-preset", "-o", path("x.artcam")}).exit_code != 0);
  }

  void usageErrorsExitWithTwo() {
    QCOMPARE(artcamCli({"fit"}).exit_code, 2);
    QCOMPARE(artcamCli({"fit", "a.csv", "-o", "x.artcam", "--size", "12by4"}).exit_code, 2);
    QCOMPARE(artcamCli({"frobnicate"}).exit_code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCli)
#include "test_cli.moc"
