// SPDX-License-Identifier: Apache-2.0
// Robust fitting: 10 % and 30 % gross outliers among 200 noisy matches.
#include "core/fit/fit_image.h"
#include "core/fit/robust.h"
#include "core/model/frames.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <set>

using namespace artcam;

namespace {

const FrameSize kFrame{600, 400};

double rmsMapError(const Camera& a, const Camera& b) {
  double sum = 0.0;
  int n = 0;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i, ++n) {
      const Eigen::Vector2d p(600.0 * (0.05 + 0.045 * i), 400.0 * (0.05 + 0.045 * j));
      const auto ya = targetPixelFromSourcePixel(a, p), yb = targetPixelFromSourcePixel(b, p);
      if (!ya || !yb) return 1e9;
      sum += (*ya - *yb).squaredNorm();
    }
  return std::sqrt(sum / n);
}

}  // namespace

class TestRobust : public QObject {
  Q_OBJECT

 private slots:
  void recoversTheCameraDespiteOutliers_data() {
    QTest::addColumn<double>("outlier_fraction");
    QTest::newRow("10 %") << 0.10;
    QTest::newRow("30 %") << 0.30;
  }
  void recoversTheCameraDespiteOutliers() {
    QFETCH(double, outlier_fraction);
    const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.1);
    std::normal_distribution<double> noise(0.0, 0.5);
    std::vector<PointMatch> m;
    std::set<int> outliers;
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector2d s(test::uniform(0, 600), test::uniform(0, 400));
      Eigen::Vector2d t = *targetPixelFromSourcePixel(truth, s) +
                          Eigen::Vector2d(noise(test::rng()), noise(test::rng()));
      if (k < outlier_fraction * 200) {  // a wrong click: anywhere else in the image
        t = Eigen::Vector2d(test::uniform(0, 600), test::uniform(0, 400));
        outliers.insert(k);
      }
      m.push_back({s, t, true});
    }
    FitOptions plain;
    plain.model = ModelClass::Quadratic;
    const FitSummary naive = fitImageCamera(m, kFrame, kFrame, plain);
    FitOptions robust = plain;
    robust.robust = true;
    robust.robust_threshold_px = 2.0;
    const FitSummary s = fitImageCamera(m, kFrame, kFrame, robust);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    const double err = rmsMapError(s.camera, truth);
    qInfo("outliers %.0f%%: robust map error %.3f px (non-robust %.1f px), %zu inliers; %s",
          outlier_fraction * 100, err, naive.status.ok ? rmsMapError(naive.camera, truth) : -1.0,
          s.record.inliers.size(), s.record.reason.c_str());
    QVERIFY2(err < 0.3, qPrintable(QString::number(err)));
    // The inliers are the true inliers, less a few whose noise put them past the threshold.
    int wrong = 0;
    for (int k : s.record.inliers) wrong += outliers.count(k) ? 1 : 0;
    QVERIFY(wrong <= 2);  // an outlier can land near its true position by chance
    QVERIFY(static_cast<int>(s.record.inliers.size()) >= 200 - static_cast<int>(outliers.size()) - 5);
    QCOMPARE(s.record.residuals_px.size(), size_t(200));
  }

  // The adaptive iteration count, against the closed form log(1 - p) / log(1 - w^k).
  void iterationCountFollowsTheInlierShare() {
    QVERIFY(std::abs(ransacIterations(0.99, 0.5, 4, 1000000) - std::log(0.01) / std::log(1.0 - 1.0 / 16)) < 1e-9);
    QCOMPARE(ransacIterations(0.999, 1.0, 9, 10000), 0.0);
    QCOMPARE(ransacIterations(0.999, 0.0, 9, 10000), 10000.0);
    // A first sample with 9 inliers of 1999: w^9 ≈ 1e-21, so 1 - w^9 rounds to 1; the count
    // must be the cap, not -inf (which once ended the search after one draw).
    QCOMPARE(ransacIterations(0.999, 9.0 / 1999.0, 9, 10000), 10000.0);
    QVERIFY(ransacIterations(0.999, 0.8, 9, 10000) > 40.0);
  }
};

QTEST_GUILESS_MAIN(TestRobust)
#include "test_robust.moc"
