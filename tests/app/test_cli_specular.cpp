// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 6 from the command line, as a user runs it: `artcam sample specular-pair`,
// `artcam fit --block colour` on its samples and `artcam warp` of the silver photo; the relit
// photo is measured against the green one by ΔE00 over the reflector.
#include "core/colour/colour_difference.h"
#include "core/io/image_io.h"

#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

class TestCliSpecular : public QObject {
  Q_OBJECT

 private slots:
  void relightsTheSilverAsTheGreen() {
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "specular-pair", "-o", dir.path(), "--size", "192x192"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"fit", "--block", "colour", dir.filePath("specular-samples.csv"), "--size",
                   "192x192", "-o", dir.filePath("relight.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("quadratic colour map"), qPrintable(r.out));
    r = artcamCli({"warp", dir.filePath("silver.png"), dir.filePath("relight.artcam"), "-o",
                   dir.filePath("relit.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const auto silver = readImage(dir.filePath("silver.png").toStdString());
    const auto green = readImage(dir.filePath("green.png").toStdString());
    const auto relit = readImage(dir.filePath("relit.png").toStdString());
    QVERIFY(silver.ok() && green.ok() && relit.ok());
    QCOMPARE(relit->image.width, 192);
    double relit_sum = 0, silver_sum = 0;
    int n = 0;
    for (int y = 0; y < 192; ++y)
      for (int x = 0; x < 192; ++x) {
        const float* s = silver->image.pixel(x, y);
        if (s[0] + s[1] + s[2] < 0.02f) continue;  // the black backdrop
        const float* g = green->image.pixel(x, y);
        const float* o = relit->image.pixel(x, y);
        const Eigen::Vector3d truth(g[0], g[1], g[2]);
        relit_sum += deltaE2000(Eigen::Vector3d(o[0], o[1], o[2]), truth);
        silver_sum += deltaE2000(Eigen::Vector3d(s[0], s[1], s[2]), truth);
        ++n;
      }
    QVERIFY(n > 10000);
    const double relit_mean = relit_sum / n, silver_mean = silver_sum / n;
    qInfo("mean dE00 to the green photo: silver %.1f, relit %.2f (%d px, 8-bit PNGs)", silver_mean,
          relit_mean, n);
    QVERIFY2(relit_mean < 2.0, qPrintable(QString::number(relit_mean)));
    QVERIFY(silver_mean > 10.0 * relit_mean);
  }

  void refusesWhatItCannotMake() {
    QTemporaryDir dir;
    QCOMPARE(artcamCli({"sample", "specular-pair", "-o", dir.path(), "--size", "200x100"}).exit_code, 2);
    QCOMPARE(artcamCli({"sample", "specular-pair", "-o", dir.path(), "--squares", "8"}).exit_code, 2);
    QVERIFY(!QFile::exists(dir.filePath("silver.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliSpecular)
#include "test_cli_specular.moc"
