// SPDX-License-Identifier: Apache-2.0
// parallelForRows (core/util/parallel.h) on its pool of helper threads: every row once, from
// several callers at once, nested, with exceptions and with progress and cancel on the
// calling thread. The sanitizer job runs this under TSan.
#include "core/util/parallel.h"

#include <QtTest/QtTest>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace artcam;

namespace {

// How many times each of `rows` rows was handed out.
std::vector<int> countRows(int rows, int band_rows, int threads) {
  std::vector<std::atomic<int>> seen(static_cast<size_t>(rows));
  ParallelOptions o;
  o.threads = threads;
  o.band_rows = band_rows;
  const bool finished = parallelForRows(rows, o, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) ++seen[static_cast<size_t>(y)];
  });
  std::vector<int> counts;
  for (const auto& s : seen) counts.push_back(s.load());
  if (!finished) counts.clear();
  return counts;
}

bool eachOnce(const std::vector<int>& counts, int rows) {
  if (static_cast<int>(counts.size()) != rows) return false;
  for (int c : counts)
    if (c != 1) return false;
  return true;
}

}  // namespace

class TestParallel : public QObject {
  Q_OBJECT

 private slots:
  void everyRowOnce() {
    for (const int threads : {1, 2, 3, 8})
      for (const int band_rows : {1, 7, 16, 1000}) {
        QVERIFY2(eachOnce(countRows(997, band_rows, threads), 997),
                 qPrintable(QString("threads %1, bands of %2").arg(threads).arg(band_rows)));
      }
  }

  void manyCallersAtOnce() {
    // Four threads post jobs to the one pool at the same time, again and again: each call
    // still sees its own rows once and returns.
    std::atomic<int> good{0};
    std::vector<std::thread> callers;
    for (int c = 0; c < 4; ++c)
      callers.emplace_back([&] {
        for (int k = 0; k < 50; ++k) good += eachOnce(countRows(300, 5, 3), 300) ? 1 : 0;
      });
    for (std::thread& t : callers) t.join();
    QCOMPARE(good.load(), 200);
  }

  void aBandMayCallItAgain() {
    // A band that runs a parallel pass of its own (a helper thread posting a job) finishes.
    std::atomic<int> inner{0};
    ParallelOptions o;
    o.threads = 2;
    o.band_rows = 1;
    QVERIFY(parallelForRows(8, o, [&](int, int) {
      for (int c : countRows(50, 3, 2)) inner += c;
    }));
    QCOMPARE(inner.load(), 8 * 50);
  }

  void anExceptionReachesTheCaller() {
    ParallelOptions o;
    o.threads = 2;
    o.band_rows = 1;
    bool thrown = false;
    try {
      parallelForRows(100, o, [](int y0, int) {
        if (y0 == 37) throw std::runtime_error("band 37");
      });
    } catch (const std::runtime_error& e) {
      thrown = std::string(e.what()) == "band 37";
    }
    QVERIFY(thrown);
    QVERIFY(eachOnce(countRows(100, 1, 2), 100));  // the pool still serves
  }

  void progressOnTheCallingThreadEndsAtOne() {
    ParallelOptions o;
    o.threads = 2;
    o.band_rows = 4;
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<double> seen;
    bool same_thread = true;
    o.progress = [&](double f) {
      same_thread = same_thread && std::this_thread::get_id() == caller;
      seen.push_back(f);
      return true;
    };
    QVERIFY(parallelForRows(400, o, [](int, int) { std::this_thread::yield(); }));
    QVERIFY(same_thread);
    QVERIFY(!seen.empty());
    QCOMPARE(seen.back(), 1.0);
    for (size_t k = 1; k < seen.size(); ++k) QVERIFY(seen[k] >= seen[k - 1]);
  }

  void aStopStartsNoNewBand() {
    // One thread: the first band runs, its report says stop, nothing else runs.
    ParallelOptions o;
    o.threads = 1;
    o.band_rows = 10;
    std::atomic<int> rows_run{0};
    int reports = 0;
    o.progress = [&](double) {
      ++reports;
      return false;
    };
    QVERIFY(!parallelForRows(100, o, [&](int y0, int y1) { rows_run += y1 - y0; }));
    QCOMPARE(rows_run.load(), 10);
    QCOMPARE(reports, 1);
    // Two threads: the call still says it was cancelled.
    o.threads = 2;
    QVERIFY(!parallelForRows(1000, o, [&](int, int) {}));
  }
};

QTEST_GUILESS_MAIN(TestParallel)
#include "test_parallel.moc"
