// SPDX-License-Identifier: Apache-2.0
// The one K-fold cross-validation of the model choices (core/fit/cross_validation.h): fold f
// holds out k % K == f, every item is held out exactly once, a failed fold or too small a
// training set gives no result. The truth for the sum is the closed form of leave-one-out for
// the mean: holding out x_k from n values leaves the mean off by n/(n-1) (x_k - x̄).
#include "core/fit/cross_validation.h"

#include <QtTest/QtTest>

#include <cmath>
#include <numeric>
#include <set>

using namespace artcam;

class TestCrossValidation : public QObject {
  Q_OBJECT

 private slots:
  void foldsInterleaveAndCoverEveryItemOnce() {
    constexpr int kItems = 23, kFolds = 10;
    std::vector<std::pair<std::vector<int>, std::vector<int>>> folds;  // (train, held) in order
    const auto sum =
        crossValidatedSum(kItems, kFolds, 1,
                          [&](const std::vector<int>& train,
                              const std::vector<int>& held) -> std::optional<std::vector<double>> {
                            folds.emplace_back(train, held);
                            return std::vector<double>(held.size(), 1.0);
                          });
    QCOMPARE(folds.size(), size_t(kFolds));
    std::multiset<int> held_out;
    for (int f = 0; f < kFolds; ++f) {
      const auto& [train, held] = folds[static_cast<size_t>(f)];
      for (int k : held) QCOMPARE(k % kFolds, f);
      for (int k : train) QVERIFY(k % kFolds != f);
      QCOMPARE(train.size() + held.size(), size_t(kItems));
      held_out.insert(held.begin(), held.end());
    }
    QVERIFY(sum.has_value());
    QCOMPARE(*sum, double(kItems));  // one error of 1 per item
    QCOMPARE(held_out.size(), size_t(kItems));
    for (int k = 0; k < kItems; ++k) QCOMPARE(held_out.count(k), size_t(1));
    QCOMPARE(smallestTrainingSet(kItems, kFolds), 23 - 3);
  }

  void leaveOneOutOfTheMeanIsTheClosedForm() {
    const std::vector<double> x = {0.5, 2.0, -1.25, 3.5, 0.0, 7.0, 1.5};
    const int n = static_cast<int>(x.size());
    const auto sum =
        crossValidatedSum(n, n, 1,
                          [&](const std::vector<int>& train,
                              const std::vector<int>& held) -> std::optional<std::vector<double>> {
                            double mean = 0.0;
                            for (int k : train) mean += x[k];
                            mean /= static_cast<double>(train.size());
                            std::vector<double> e;
                            for (int k : held) e.push_back((x[k] - mean) * (x[k] - mean));
                            return e;
                          });
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
    double expected = 0.0;
    for (double v : x) expected += std::pow(n / (n - 1.0) * (v - mean), 2);
    QVERIFY(sum.has_value());
    QVERIFY2(std::abs(*sum - expected) <= 1e-12 * expected,
             qPrintable(QString("%1 vs %2").arg(*sum).arg(expected)));
  }

  void noResultWithoutEnoughTrainingOrAfterAFailedFold() {
    int calls = 0;
    const FoldErrors count =
        [&](const std::vector<int>&,
            const std::vector<int>& held) -> std::optional<std::vector<double>> {
      ++calls;
      return std::vector<double>(held.size(), 0.0);
    };
    QVERIFY(!crossValidatedSum(10, 10, 10, count));  // each fold trains on 9
    QVERIFY(crossValidatedSum(10, 10, 9, count));
    QVERIFY(!crossValidatedSum(1, 1, 0, count));  // one fold validates nothing
    QCOMPARE(calls, 10);
    calls = 0;
    const auto failing =
        crossValidatedSum(12, 4, 1,
                          [&](const std::vector<int>&,
                              const std::vector<int>& held) -> std::optional<std::vector<double>> {
                            if (++calls == 3) return std::nullopt;
                            return std::vector<double>(held.size(), 0.0);
                          });
    QVERIFY(!failing);
    QCOMPARE(calls, 3);  // the fourth fold is not fitted
  }
};

QTEST_APPLESS_MAIN(TestCrossValidation)
#include "test_cross_validation.moc"
