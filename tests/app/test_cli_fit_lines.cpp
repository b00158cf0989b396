// SPDX-License-Identifier: Apache-2.0
// `artcam fit --lines` end to end: edges of a straight scene photographed through a known
// barrel lens (u = U / (1 - k |U|²) from photo to scene, normalised frame, 6000×4000) are
// written as a lines CSV; the fitted camera is then applied by `artcam map` to HELD-OUT edges,
// whose straightness this file measures itself. Refusals are one line naming the file.
#include "core/model/frames.h"
#include "tests/app/cli_run.h"
#include "tests/support/straight_lines.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace artcam;
using artcam::test::artcamCli;
using artcam::test::bowOf;

namespace {

const FrameSize kFrame{6000, 4000};
const double kLensK = 0.05;

// Scene pixel → photo pixel through the inverse of the lens (closed form in |U|).
Eigen::Vector2d photoFromScene(const Eigen::Vector2d& scene_px) {
  return pixelFromNormalized(
      kFrame, test::radialPhotoFromScene(kLensK, normalizedFromPixel(kFrame, scene_px)));
}

std::vector<Eigen::Vector2d> edgePoints(Eigen::Vector2d a, Eigen::Vector2d b, int n) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < n; ++k) out.push_back(photoFromScene(a + (b - a) * (k / (n - 1.0))));
  return out;
}

bool writeFile(const QString& path, const QByteArray& text) {
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly)) return false;
  return f.write(text) == text.size();
}

QByteArray linesCsv() {
  QByteArray csv = "line,x,y\n";
  const auto add = [&](const char* label, Eigen::Vector2d a, Eigen::Vector2d b, int n) {
    for (const Eigen::Vector2d& p : edgePoints(a, b, n)) {
      char row[160];
      std::snprintf(row, sizeof row, "%s,%.9f,%.9f\n", label, p.x(), p.y());
      csv += row;
    }
  };
  add("top", {100, 150}, {5900, 150}, 30);
  add("sill", {100, 2900}, {5900, 2900}, 30);
  add("left", {200, 100}, {200, 3900}, 25);
  add("right", {5800, 100}, {5800, 3900}, 25);
  add("roof", {150, 1900}, {2900, 150}, 25);
  return csv;
}

}  // namespace

class TestCliFitLines : public QObject {
  Q_OBJECT

 private slots:
  void heldOutEdgesComeOutStraight() {
    QTemporaryDir dir;
    QVERIFY(writeFile(dir.filePath("lines.csv"), linesCsv()));
    const auto r = artcamCli({"fit", "--lines", dir.filePath("lines.csv"), "-o",
                              dir.filePath("lens.artcam"), "--size", "6000x4000", "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["model"].toString(), QString("radial"));
    QVERIFY(std::abs(j["radial_k"].toDouble() - kLensK) < 1e-6);
    const QJsonArray lines = j["lines"].toArray();
    QCOMPARE(lines.size(), 5);
    QCOMPARE(lines[0].toObject()["line"].toString(), QString("top"));
    QCOMPARE(lines[0].toObject()["points"].toInt(), 30);
    QVERIFY(lines[0].toObject()["bow_before_px"].toDouble() > 20.0);
    QVERIFY(j["max_bow_px"].toDouble() < 0.01);

    // Held-out edges through `artcam map`: an oblique one, a low row and a column (none through
    // the centre, which the lens keeps straight anyway).
    const std::vector<std::vector<Eigen::Vector2d>> held_out = {
        edgePoints({300, 1500}, {3500, 3800}, 40), edgePoints({300, 3400}, {5700, 3400}, 40),
        edgePoints({700, 200}, {700, 3800}, 40)};
    for (const auto& edge : held_out) {
      QByteArray csv = "x,y\n";
      for (const auto& p : edge) csv += QByteArray::number(p.x(), 'g', 17) + "," +
                                        QByteArray::number(p.y(), 'g', 17) + "\n";
      QVERIFY(writeFile(dir.filePath("edge.csv"), csv));
      QVERIFY2(bowOf(edge) > 2.0, qPrintable(QString::number(bowOf(edge))));
      const auto m = artcamCli({"map", dir.filePath("lens.artcam"), dir.filePath("edge.csv")});
      QVERIFY2(m.exit_code == 0, qPrintable(m.err));
      std::vector<Eigen::Vector2d> mapped;
      for (const QString& row : m.out.split('\n', Qt::SkipEmptyParts)) {
        const QStringList f = row.split(',');
        bool ok1 = false, ok2 = false;
        if (f.size() < 4) continue;
        const double x = f[2].toDouble(&ok1), y = f[3].toDouble(&ok2);
        if (ok1 && ok2) mapped.emplace_back(x, y);
      }
      QCOMPARE(mapped.size(), edge.size());
      QVERIFY2(bowOf(mapped) <= 0.5, qPrintable(QString::number(bowOf(mapped))));
    }
  }

  void textReportAndPairs() {
    QTemporaryDir dir;
    QVERIFY(writeFile(dir.filePath("lines.csv"), linesCsv()));
    // Pairs from the lens itself: the quadratic then honours both.
    QByteArray pairs = "src_x,src_y,dst_x,dst_y\n";
    for (const Eigen::Vector2d& scene : {Eigen::Vector2d(800, 600), Eigen::Vector2d(5200, 500),
                                         Eigen::Vector2d(5100, 3500), Eigen::Vector2d(900, 3300),
                                         Eigen::Vector2d(3000, 2000)}) {
      const Eigen::Vector2d photo = photoFromScene(scene);
      pairs += QByteArray::number(photo.x(), 'g', 17) + "," + QByteArray::number(photo.y(), 'g', 17) +
               "," + QByteArray::number(scene.x(), 'g', 17) + "," +
               QByteArray::number(scene.y(), 'g', 17) + "\n";
    }
    QVERIFY(writeFile(dir.filePath("pairs.csv"), pairs));
    const auto r = artcamCli({"fit", "--lines", dir.filePath("lines.csv"), dir.filePath("pairs.csv"),
                              "-o", dir.filePath("lens.artcam"), "--size", "6000x4000"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.startsWith("quadratic from 5 lines (135 points)"), qPrintable(r.out));
    QVERIFY2(r.out.contains("5 pairs RMS"), qPrintable(r.out));
    QVERIFY2(r.out.contains("line roof: 25 points, bow "), qPrintable(r.out));
    // The output exists now: a second run needs --overwrite.
    const auto again = artcamCli({"fit", "--lines", dir.filePath("lines.csv"), "-o",
                                  dir.filePath("lens.artcam"), "--size", "6000x4000"});
    QCOMPARE(again.exit_code, 1);
  }

  void refusalsAreOneLineNamingTheFile() {
    QTemporaryDir dir;
    QVERIFY(writeFile(dir.filePath("bad.csv"), "line,x,y\na,1,2\na,zz,3\n"));
    auto r = artcamCli({"fit", "--lines", dir.filePath("bad.csv"), "-o", dir.filePath("o.artcam"),
                        "--size", "600x400"});
    QCOMPARE(r.exit_code, 1);
    QCOMPARE(r.err.trimmed().count('\n'), 0);
    QVERIFY2(r.err.contains(dir.filePath("bad.csv") + ":3: column 2 (x): not a number"),
             qPrintable(r.err));

    QVERIFY(writeFile(dir.filePath("short.csv"), "line,x,y\nedge,10,20\nedge,300,25\n"));
    r = artcamCli({"fit", "--lines", dir.filePath("short.csv"), "-o", dir.filePath("o.artcam"),
                   "--size", "600x400"});
    QCOMPARE(r.exit_code, 1);
    QCOMPARE(r.err.trimmed().count('\n'), 0);
    QVERIFY2(r.err.contains(dir.filePath("short.csv")) && r.err.contains("\"edge\" has 2 points"),
             qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("o.artcam")));

    r = artcamCli({"fit", "--lines", dir.filePath("short.csv"), "-o", dir.filePath("o.artcam"),
                   "--size", "600x400", "--model", "homography"});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("auto, radial or quadratic"), qPrintable(r.err));
  }
};

QTEST_GUILESS_MAIN(TestCliFitLines)
#include "test_cli_fit_lines.moc"
