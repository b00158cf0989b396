// SPDX-License-Identifier: Apache-2.0
// The 8-bit quantiser's table against the formula it replaces (encode, round to float, ⌊255 e + ½⌋)
// for each transfer the writers use: at every level's transition, found here by bisecting
// values (not the table's bit patterns) and probed a few doubles either side, on a dense sweep,
// and at the special values.
#include "core/colour/quantise8.h"

#include <QtTest/QtTest>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace artcam;

namespace {

std::vector<Transfer> transfers() {
  return {Transfer::srgb(), Transfer::linear(), Transfer{Transfer::Kind::Rec709, 1.0},
          Transfer{Transfer::Kind::Gamma, 2.2}, Transfer{Transfer::Kind::Gamma, 1.8}};
}

// Values where the exact level first reaches k: bisection on [0, 1] down to adjacent doubles.
double transition(const Transfer& t, int k) {
  double lo = 0.0, hi = 1.0;
  while (std::nextafter(lo, 2.0) < hi) {
    const double mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) break;
    (Quantise8::exact(t, mid) >= k ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

class TestQuantise8 : public QObject {
  Q_OBJECT

 private slots:
  void agreesAtEveryTransition() {
    for (const Transfer& t : transfers()) {
      const Quantise8 q(t);
      int mismatches = 0;
      for (int k = 1; k <= 255; ++k) {
        double v = transition(t, k);
        for (int step = 0; step < 4; ++step) v = std::nextafter(v, -1.0);
        for (int probe = 0; probe < 9; ++probe, v = std::nextafter(v, 2.0))
          if (q(v) != Quantise8::exact(t, v)) ++mismatches;
      }
      QVERIFY2(mismatches == 0, qPrintable(QString("%1 mismatches, transfer %2")
                                               .arg(mismatches)
                                               .arg(QString::fromStdString(t.colourSpaceName()))));
    }
  }

  void agreesOnASweepAndSpecialValues() {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> wide(-0.25, 1.25), near_zero(0.0, 1e-3);
    const double specials[] = {0.0, -0.0, 1.0, -1.0, 1e-300, 4.9e-324, 0.5, 0.999999999,
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::quiet_NaN()};
    for (const Transfer& t : transfers()) {
      const Quantise8 q(t);
      for (const double v : specials) QCOMPARE(int(q(v)), int(Quantise8::exact(t, v)));
      QCOMPARE(int(q(std::numeric_limits<double>::quiet_NaN())), 0);
      QCOMPARE(int(q(std::numeric_limits<double>::infinity())), 255);
      for (int i = 0; i < 200000; ++i) {
        const double v = i % 4 ? wide(random) : near_zero(random);
        if (q(v) != Quantise8::exact(t, v))
          QFAIL(qPrintable(QString("%1 at %2: %3 against %4")
                               .arg(QString::fromStdString(t.colourSpaceName()))
                               .arg(v, 0, 'g', 17)
                               .arg(q(v))
                               .arg(Quantise8::exact(t, v))));
      }
    }
  }
};

QTEST_GUILESS_MAIN(TestQuantise8)
#include "test_quantise8.moc"
