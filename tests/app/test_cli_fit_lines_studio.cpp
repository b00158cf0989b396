// SPDX-License-Identifier: Apache-2.0
// The studio and `artcam fit --lines` make one camera from one set of lines: the textbook
// plumb-line set (two horizontal and two vertical grid lines, tests/support/barrel_grid.h)
// traced on a barrel grid is saved as a studio project, exported with `artcam export
// --camera-out` (the studio's own document fit, the one its export renders) and fitted with
// `artcam fit --lines`; the two cameras must agree everywhere on the photo, and the grid they
// correct must keep its 90 px spacing within 3 %.
#include "core/io/artcam_file.h"
#include "tests/app/cli_run.h"
#include "tests/support/barrel_grid.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QTemporaryDir>

#include <cstdio>
#include <string>

using namespace artcam;
using artcam::test::artcamCli;
using artcam::test::BarrelGrid;

namespace {

bool writeFile(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly)) return false;
  return f.write(bytes) == bytes.size();
}

QByteArray number(double v) { return QByteArray::number(v, 'g', 17); }

QByteArray linesCsv(const std::vector<LineTrace>& lines) {
  QByteArray csv = "line,x,y\n";
  for (const LineTrace& l : lines)
    for (const Eigen::Vector2d& p : l.points)
      csv += QByteArray::fromStdString(l.label) + "," + number(p.x()) + "," + number(p.y()) + "\n";
  return csv;
}

QByteArray projectJson(const std::vector<LineTrace>& lines, const char* line_model) {
  QByteArray json =
      "{\"format\": \"artcam-studio-project\", \"version\": 4, \"photo\": "
      "\"grid.ppm\", \"model\": \"auto\", \"pairs\": [], ";
  if (line_model) json += QByteArray("\"line_model\": \"") + line_model + "\", ";
  json += "\"lines\": [";
  for (size_t i = 0; i < lines.size(); ++i) {
    json += (i ? ", " : "") + QByteArray("{\"label\": \"") +
            QByteArray::fromStdString(lines[i].label) + "\", \"enabled\": true, \"points\": [";
    for (size_t k = 0; k < lines[i].points.size(); ++k)
      json += (k ? ", [" : "[") + number(lines[i].points[k].x()) + ", " +
              number(lines[i].points[k].y()) + "]";
    json += "]}";
  }
  return json + "]}";
}

// A grey photo of the grid's size (its pixels do not matter to the fit).
QByteArray greyPpm(FrameSize f) {
  QByteArray ppm =
      "P6\n" + QByteArray::number(f.width) + " " + QByteArray::number(f.height) + "\n255\n";
  ppm += QByteArray(f.width * f.height * 3, char(128));
  return ppm;
}

double worstDifferencePx(const Camera& a, const Camera& b, FrameSize f) {
  double worst = 0;
  for (int j = 0; j <= 12; ++j)
    for (int i = 0; i <= 16; ++i) {
      const Eigen::Vector2d p(f.width * i / 16.0, f.height * j / 12.0);
      const auto ya = targetPixelFromSourcePixel(a, p), yb = targetPixelFromSourcePixel(b, p);
      if (!ya || !yb) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, (*ya - *yb).norm());
    }
  return worst;
}

}  // namespace

class TestCliFitLinesStudio : public QObject {
  Q_OBJECT

 private slots:
  void oneCameraForOneSetOfLines_data() {
    QTest::addColumn<int>("seed");
    QTest::addColumn<QString>("model");
    for (int seed : {1, 2, 3}) {
      QTest::addRow("auto, seed %d", seed) << seed << "auto";
      QTest::addRow("radial, seed %d", seed) << seed << "radial";
    }
  }
  void oneCameraForOneSetOfLines() {
    QFETCH(int, seed);
    QFETCH(QString, model);
    const BarrelGrid grid;
    const std::vector<LineTrace> lines = grid.plumbLines(true, seed);
    QTemporaryDir dir;
    QVERIFY(writeFile(dir.filePath("grid.ppm"), greyPpm(grid.frame)));
    QVERIFY(writeFile(dir.filePath("lines.csv"), linesCsv(lines)));
    const QByteArray m = model.toUtf8();
    QVERIFY(writeFile(dir.filePath("grid.artcamproj"),
                      projectJson(lines, model == "auto" ? nullptr : m.constData())));

    const auto fit =
        artcamCli({"fit", "--lines", dir.filePath("lines.csv"), "-o", dir.filePath("cli.artcam"),
                   "--size", "960x720", "--model", model, "--quiet"});
    QVERIFY2(fit.exit_code == 0, qPrintable(fit.err));
    const auto exported =
        artcamCli({"export", dir.filePath("grid.artcamproj"), "-o", dir.filePath("out.png"),
                   "--camera-out", dir.filePath("studio.artcam"), "--quiet"});
    QVERIFY2(exported.exit_code == 0, qPrintable(exported.err));
    const Result<Artcam> cli = readArtcam(dir.filePath("cli.artcam").toStdString());
    const Result<Artcam> studio = readArtcam(dir.filePath("studio.artcam").toStdString());
    QVERIFY2(cli.status.ok, cli.status.message.c_str());
    QVERIFY2(studio.status.ok, studio.status.message.c_str());

    const double apart = worstDifferencePx(cli.value->main(), studio.value->main(), grid.frame);
    const auto c = grid.check(cli.value->main());
    qInfo(
        "%s seed %d: studio and CLI %.3g px apart; spacing %.1f–%.1f px (truth 90), "
        "covered %.1f %%",
        qPrintable(model), seed, apart, c.min_spacing_px, c.max_spacing_px, 100 * c.covered);
    QVERIFY2(apart < 1e-6, qPrintable(QString::number(apart)));
    QVERIFY2(c.worst_ratio_error <= 0.03, qPrintable(QString::number(c.worst_ratio_error)));
    QVERIFY2(c.covered >= 0.99, qPrintable(QString::number(c.covered)));
  }
};

QTEST_GUILESS_MAIN(TestCliFitLinesStudio)
#include "test_cli_fit_lines_studio.moc"
