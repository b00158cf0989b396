// SPDX-License-Identifier: Apache-2.0
// CIEDE2000 against the published test data of Sharma, Wu & Dalal (Color Res. Appl. 30(1),
// 2005, Table 1: all 34 pairs, dE00 to 4 decimals), an independent source; CIELAB of sRGB
// primaries against published values.
#include "core/colour/colour_difference.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

struct Pair {
  double l1, a1, b1, l2, a2, b2, de;
};

// Sharma, Wu & Dalal (2005), Table 1.
const Pair kSharma[] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

}  // namespace

class TestColourDifference : public QObject {
  Q_OBJECT

 private slots:
  void ciede2000MatchesThePublishedTestData() {
    int index = 0;
    for (const Pair& p : kSharma) {
      ++index;
      const Lab first{p.l1, p.a1, p.b1}, second{p.l2, p.a2, p.b2};
      const double de = ciede2000(first, second);
      // Published to 4 decimals: half a unit in the last place, plus round-off.
      QVERIFY2(std::abs(de - p.de) <= 0.5e-4 + 1e-9,
               qPrintable(QString("pair %1: %2, published %3").arg(index).arg(de, 0, 'f', 6).arg(p.de)));
      // The formula is symmetric in its arguments (the hue mean and difference both are).
      QVERIFY(std::abs(ciede2000(second, first) - de) < 1e-12);
    }
    QCOMPARE(index, 34);
  }

  void identicalColoursDifferByZero() {
    QCOMPARE(ciede2000({50, 10, -20}, {50, 10, -20}), 0.0);
    QCOMPARE(deltaE2000(Eigen::Vector3d(0.2, 0.4, 0.6), Eigen::Vector3d(0.2, 0.4, 0.6)), 0.0);
  }

  void labOfTheSrgbWhiteAndPrimaries() {
    // White (1, 1, 1) is the reference white.
    const Lab white = labFromLinearRgb(Eigen::Vector3d::Ones());
    QVERIFY(std::abs(white.l - 100.0) < 1e-9 && std::abs(white.a) < 1e-9 && std::abs(white.b) < 1e-9);
    const Lab black = labFromLinearRgb(Eigen::Vector3d::Zero());
    QVERIFY(std::abs(black.l) < 1e-12);
    // Published CIELAB (D65) of the sRGB primaries: red 53.24, 80.09, 67.20; green 87.73,
    // -86.18, 83.18; blue 32.30, 79.19, -107.86. Sources round the D65 white differently in its
    // 4th digit (we take the matrix's own white, M·(1, 1, 1)), which moves a*, b* by up to 0.03.
    const struct {
      Eigen::Vector3d rgb;
      double l, a, b;
    } primaries[] = {{{1, 0, 0}, 53.24, 80.09, 67.20},
                     {{0, 1, 0}, 87.73, -86.18, 83.18},
                     {{0, 0, 1}, 32.30, 79.19, -107.86}};
    for (const auto& p : primaries) {
      const Lab lab = labFromLinearRgb(p.rgb);
      QVERIFY2(std::abs(lab.l - p.l) < 0.05 && std::abs(lab.a - p.a) < 0.05 &&
                   std::abs(lab.b - p.b) < 0.05,
               qPrintable(QString("%1 %2 %3").arg(lab.l).arg(lab.a).arg(lab.b)));
    }
  }

  void outOfGamutColoursGiveFiniteDifferences() {
    for (const Eigen::Vector3d& c : {Eigen::Vector3d(-0.1, 0.5, 0.2), Eigen::Vector3d(2.0, -1.0, 0.0),
                                    Eigen::Vector3d(0.0, 0.0, -0.001)}) {
      const double de = deltaE2000(c, Eigen::Vector3d(0.3, 0.3, 0.3));
      QVERIFY(std::isfinite(de) && de > 0.0);
    }
  }
};

QTEST_GUILESS_MAIN(TestColourDifference)
#include "test_colour_difference.moc"
