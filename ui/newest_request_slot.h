// SPDX-License-Identifier: Apache-2.0
// The request half of the studio's newest-request workers (after Qt's Mandelbrot example): one
// pending slot where the newest request wins, atomic restart/abort flags the job in flight
// polls between tiles, and the thread started on the first request and joined on shutdown (the
// only wait, when the owner goes). NewestRequestWorker (newest_request_worker.h) loops on
// take() and is every worker's exception boundary. One-shot jobs use background_job.h instead.
//
// The slot's lock and wait are std::mutex and std::condition_variable, not QMutex and
// QWaitCondition: QWaitCondition::wait releases and retakes the mutex inside libQt6Core, where
// ThreadSanitizer cannot see it, so every hand-over looked like a race between two holders of
// one lock. pthread's wait is seen, and CI's TSan job checks this hand-over for real.
#pragma once

#include <QThread>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <utility>

namespace artcam::ui {

template <class Request>
class NewestRequestSlot {
 public:
  // GUI thread: replaces the pending request; the job in flight sees keepGoing() turn false.
  void put(Request request, QThread& thread) {
    const std::lock_guard<std::mutex> locker(mutex_);
    pending_ = std::move(request);
    if (!thread.isRunning()) {
      abort_ = false;
      thread.start(QThread::LowPriority);
    } else {
      restart_ = true;
      condition_.notify_one();
    }
  }

  // GUI thread: drops the pending request, stops the job in flight and joins the thread.
  void shutdown(QThread& thread) {
    {
      const std::lock_guard<std::mutex> locker(mutex_);
      abort_ = true;
      pending_.reset();
      condition_.notify_one();
    }
    thread.wait();
  }

  // Worker thread: waits for the next request; empty when shutting down (run() then returns).
  std::optional<Request> take() {
    std::unique_lock<std::mutex> locker(mutex_);
    condition_.wait(locker, [this] { return pending_.has_value() || abort_.load(); });
    if (abort_) return std::nullopt;
    std::optional<Request> job = std::move(pending_);
    pending_.reset();
    restart_ = false;
    return job;
  }

  // Worker thread, between tiles: false once a newer request or a shutdown arrived.
  bool keepGoing() const { return !restart_.load() && !abort_.load(); }

 private:
  std::mutex mutex_;
  std::condition_variable condition_;
  std::optional<Request> pending_;  // guarded by mutex_
  std::atomic<bool> restart_{false};
  std::atomic<bool> abort_{false};
};

}  // namespace artcam::ui
