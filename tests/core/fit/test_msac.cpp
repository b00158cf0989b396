// SPDX-License-Identifier: Apache-2.0
// The one MSAC search (core/fit/msac.h), generic over what is fitted: here lines y = a x + b
// through 2-point minimal sets, among planted outliers far off the line. The truth is the
// planted sets: the inliers found are exactly the points on the line, and the same seed gives
// the same search.
#include "core/fit/msac.h"

#include <QtTest/QtTest>

#include <cmath>
#include <limits>

using namespace artcam;

namespace {

struct Points {
  std::vector<double> x, y;
};

// 60 points on y = 0.5 x + 2 (within ±0.05), every fourth moved 5 to 20 off it.
Points plantedLine(std::vector<int>& on_line) {
  Points p;
  for (int k = 0; k < 60; ++k) {
    const double x = 0.25 * k - 7.0;
    double y = 0.5 * x + 2.0 + 0.05 * std::sin(1.7 * k);
    if (k % 4 == 1)
      y += (k % 8 == 1 ? 1.0 : -1.0) * (5.0 + 0.25 * k);
    else
      on_line.push_back(k);
    p.x.push_back(x);
    p.y.push_back(y);
  }
  return p;
}

MsacScore scoreLine(const Points& p, double a, double b, double threshold) {
  MsacScore s;
  for (size_t k = 0; k < p.x.size(); ++k) {
    const double e = p.y[k] - (a * p.x[k] + b);
    s.add(static_cast<int>(k), e * e, threshold * threshold);
  }
  return s;
}

// Least squares through `set`; nothing for fewer than two distinct x.
std::optional<MsacScore> fitLine(const Points& p, const std::vector<int>& set, double threshold) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(set.size());
  for (int k : set) {
    sx += p.x[k];
    sy += p.y[k];
    sxx += p.x[k] * p.x[k];
    sxy += p.x[k] * p.y[k];
  }
  const double det = n * sxx - sx * sx;
  if (!(std::abs(det) > 1e-12)) return std::nullopt;
  const double a = (n * sxy - sx * sy) / det;
  return scoreLine(p, a, (sy - a * sx) / n, threshold);
}

}  // namespace

class TestMsac : public QObject {
  Q_OBJECT

 private slots:
  void findsThePlantedInliers() {
    std::vector<int> on_line;
    const Points p = plantedLine(on_line);
    const auto fit = [&p](const std::vector<int>& set) { return fitLine(p, set, 0.5); };
    const MsacProblem problem{static_cast<int>(p.x.size()), 2, fit, fit};
    const MsacResult r = runMsac(problem, {});
    QCOMPARE(r.inliers, on_line);
    QVERIFY(r.iterations >= 1 && r.iterations < 10000);  // stops once confident
    const MsacResult again = runMsac(problem, {});
    QCOMPARE(again.inliers, r.inliers);
    QCOMPARE(again.iterations, r.iterations);
  }

  void aScoreCapsOutliersAtTheThreshold() {
    MsacScore s;
    s.add(0, 0.25, 1.0);
    s.add(1, 4.0, 1.0);
    s.add(2, std::numeric_limits<double>::infinity(), 1.0);
    s.add(3, std::numeric_limits<double>::quiet_NaN(), 1.0);
    s.add(4, 1.0, 1.0);  // at the threshold: not an inlier
    QCOMPARE(s.cost, 0.25 + 4 * 1.0);
    QCOMPARE(s.inliers, std::vector<int>{0});
  }

  void noSampleFitsNoInliers() {
    const auto none = [](const std::vector<int>&) -> std::optional<MsacScore> {
      return std::nullopt;
    };
    MsacOptions options;
    options.max_iterations = 50;
    const MsacResult r = runMsac({10, 3, none, none}, options);
    QVERIFY(r.inliers.empty());
    QCOMPARE(r.iterations, 50);
  }
};

QTEST_APPLESS_MAIN(TestMsac)
#include "test_msac.moc"
