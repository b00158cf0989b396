// SPDX-License-Identifier: Apache-2.0
// `artcam fit` under auto on the paper's nine-point drawing (Fig 5): nine clicked pairs of a
// bulge give the quadratic camera, and --json says why with every model's error.
#include "core/model/frames.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cstdio>
#include <random>

using namespace artcam;
using artcam::test::artcamCli;

class TestCliAutoModel : public QObject {
  Q_OBJECT

 private slots:
  void nineBulgePairsFitTheQuadraticAndSayWhy() {
    // u' = u / (1 − 0.1 r²) in the normalised frame, on a jittered 3×3 grid, clicks ±0.5 px.
    const FrameSize frame{600, 400};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> jitter(0.25, 0.75), click(-0.5, 0.5);
    QByteArray csv = "src_x,src_y,dst_x,dst_y\n";
    double largest = 0.0;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector2d s(600 * (0.1 + 0.8 * (i + jitter(rng)) / 3),
                                400 * (0.1 + 0.8 * (j + jitter(rng)) / 3));
        const Eigen::Vector2d u = normalizedFromPixel(frame, s);
        const Eigen::Vector2d t = pixelFromNormalized(frame, u / (1.0 - 0.1 * u.squaredNorm()));
        largest = std::max(largest, (t - s).norm());
        char line[200];
        std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f\n", s.x(), s.y(),
                      t.x() + click(rng), t.y() + click(rng));
        csv += line;
      }
    QVERIFY(largest > 10.0);
    QTemporaryDir dir;
    QFile f(dir.filePath("bulge.csv"));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(csv);
    f.close();
    const auto r = artcamCli({"fit", dir.filePath("bulge.csv"), "-o", dir.filePath("b.artcam"),
                              "--size", "600x400", "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["model"].toString(), QString("quadratic"));
    QCOMPARE(j["criterion"].toString(), QString("aic"));
    const QString reason = j["reason"].toString();
    QVERIFY2(reason.contains("auto chose quadratic") && reason.contains("information criterion"),
             qPrintable(reason));
    const QJsonArray models = j["models"].toArray();
    QCOMPARE(models.size(), 5);
    QCOMPARE(models[4].toObject()["model"].toString(), QString("quadratic"));
    // The homography misses a bulge of more than 10 px by pixels; the quadratic nearly fits.
    QVERIFY(models[3].toObject()["rms_px"].toDouble() > 1.0);
    QVERIFY(models[4].toObject()["rms_px"].toDouble() < 1.0);
    // The project written beside it keeps the same list.
    QFile project(dir.filePath("b.artcam"));
    QVERIFY(project.open(QIODevice::ReadOnly));
    const QJsonObject fit = QJsonDocument::fromJson(project.readAll()).object()["fit"].toObject();
    QCOMPARE(fit["models"].toArray().size(), 5);
    QCOMPARE(fit["criterion"].toString(), QString("aic"));
  }
};

QTEST_GUILESS_MAIN(TestCliAutoModel)
#include "test_cli_auto_model.moc"
