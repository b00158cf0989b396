// SPDX-License-Identifier: Apache-2.0
#include "core/util/parallel.h"

#include "core/util/slot_limits.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace artcam {
namespace {

// Helper threads that outlive the calls they serve. Why: a render makes several parallel
// passes (seven for a rational lens or a piecewise camera), and starting and joining a thread
// for each is not small beside a render's time, still less a studio preview's. A call posts a
// Job asking for some helpers and works on it itself; idle pool threads join it. The pool
// starts a thread whenever the helpers asked for exceed the idle threads, so it grows to the
// most ever wanted at once and a posted job never waits for another job's helpers. A call
// closes its job when it has run out of bands: helpers that had not joined by then never
// will, and the call waits only for those inside.
//
// Waiting spins before it sleeps: an idle helper polls for a new job for kSpin before it waits
// on the condition variable, and a closing call polls for its helpers to leave before it does.
// Why: a render's passes follow each other within microseconds, sooner than a sleeping
// thread's futex wake-up would let it start its first band. Posting only wakes threads that
// sleep, so back-to-back passes make no system call. The spin costs at most kSpin of one core
// after each burst of work.
constexpr auto kSpin = std::chrono::microseconds(200);

// Polls `ready` (pausing the core between polls) until it is true or kSpin has passed.
template <class Ready>
bool spinUntil(const Ready& ready) {
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (std::chrono::steady_clock::now() >= until) return ready();
    // Let any thread that has work run first: with more threads than cores (the studio's
    // render and fit workers, each with helpers) a spinner must not hold a core.
    std::this_thread::yield();
  }
}

struct Job {
  const std::function<void()>* work = nullptr;
  int wanted = 0;                // helpers still to join; 0 once closed
  std::atomic<int> running{0};  // helpers inside work() (changed under the pool's mutex)
};

class Pool {
 public:
  static Pool& instance() {
    // Never destroyed: its threads wait for work until the process ends (they are detached).
    static Pool* pool = new Pool;
    return *pool;
  }

  void post(Job& job) {
    const std::lock_guard<std::mutex> lock(mutex_);
    open_.push_back(&job);
    wanted_ += job.wanted;
    try {
      while (idle_ + starting_ < wanted_) {
        std::thread(&Pool::serve, this).detach();
        ++starting_;
      }
    } catch (const std::system_error&) {
      // No thread to be had: the caller works on its job alone, or with threads that free up.
    }
    pending_.store(wanted_, std::memory_order_release);
    if (sleeping_ > 0) wake_.notify_all();
  }

  void close(Job& job) {
    std::unique_lock<std::mutex> lock(mutex_);
    wanted_ -= job.wanted;
    pending_.store(wanted_, std::memory_order_release);
    job.wanted = 0;
    open_.erase(std::find(open_.begin(), open_.end(), &job));
    if (job.running.load(std::memory_order_relaxed) == 0) return;
    lock.unlock();
    spinUntil([&] { return job.running.load(std::memory_order_acquire) == 0; });
    lock.lock();
    done_.wait(lock, [&] { return job.running.load(std::memory_order_relaxed) == 0; });
  }

 private:
  void serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    --starting_;
    for (;;) {
      ++idle_;
      if (wanted_ == 0) {
        lock.unlock();
        spinUntil([&] { return pending_.load(std::memory_order_acquire) > 0; });
        lock.lock();
        ++sleeping_;
        wake_.wait(lock, [&] { return wanted_ > 0; });
        --sleeping_;
      }
      --idle_;
      Job* job = nullptr;
      for (Job* j : open_)
        if (j->wanted > 0) {
          job = j;
          break;
        }
      --job->wanted;
      --wanted_;
      pending_.store(wanted_, std::memory_order_relaxed);
      job->running.fetch_add(1, std::memory_order_relaxed);
      lock.unlock();
      (*job->work)();  // catches everything itself
      lock.lock();
      if (job->running.fetch_sub(1, std::memory_order_release) == 1) done_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<Job*> open_;
  int wanted_ = 0;    // the open jobs' helpers still to join
  std::atomic<int> pending_{0};  // wanted_, for spinning threads to poll without the mutex
  int idle_ = 0;      // threads waiting for work (spinning or asleep)
  int sleeping_ = 0;  // of those, waiting on wake_
  int starting_ = 0;  // threads started that have not yet waited
};

}  // namespace

int resolveThreadCount(int threads) {
  if (threads > 0) return threads;
  return slotThreadCount();  // the CPUs this process may use, not the machine's (slot_limits.h)
}

bool parallelForRows(int rows, const ParallelOptions& options,
                     const std::function<void(int, int)>& band) {
  if (rows <= 0) return true;
  const int band_rows = std::max(1, options.band_rows);
  const int bands = (rows + band_rows - 1) / band_rows;
  const int workers = std::min(resolveThreadCount(options.threads), bands);

  std::atomic<int> next{0}, done_rows{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::exception_ptr error;  // guarded by mutex
  const auto fail = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!error) error = std::current_exception();
    stop = true;
  };
  // One band, or none left: false.
  const auto runBand = [&] {
    if (stop.load(std::memory_order_relaxed)) return false;
    const int b = next.fetch_add(1);
    if (b >= bands) return false;
    const int y0 = b * band_rows, y1 = std::min(rows, y0 + band_rows);
    try {
      band(y0, y1);
    } catch (...) {
      fail();
    }
    done_rows += y1 - y0;
    return true;
  };
  const std::function<void()> help = [&] {
    while (runBand()) {
    }
  };

  // The caller works as one of the workers; it also reports progress, after each band it ran,
  // so the callback never has to be thread-safe.
  Job job;
  job.work = &help;
  job.wanted = workers - 1;
  if (workers > 1) Pool::instance().post(job);
  bool cancelled = false;
  int reported = -1;
  const auto report = [&] {
    const int done = done_rows.load();
    if (!options.progress || stop.load() || done == reported) return;
    reported = done;
    try {
      if (!options.progress(static_cast<double>(done) / rows)) {
        cancelled = true;
        stop = true;
      }
    } catch (...) {
      fail();
    }
  };
  while (runBand()) report();
  if (workers > 1) Pool::instance().close(job);
  // The last report, after every band (1.0 unless stopped) when the helpers finished some
  // after the caller's last; a "stop" here is still honoured.
  report();
  if (error) std::rethrow_exception(error);
  return !cancelled;
}

}  // namespace artcam
