// SPDX-License-Identifier: Apache-2.0
// A hand-over queue between two pipeline stages (artcam batch) with a fixed capacity, so
// the images in flight stay bounded. One producer, one consumer. The producer waits for
// space BEFORE it makes the next item (waitForSpace), so with capacity 1 a stage holds at most
// the item it works on plus one made ahead: decode, render and encode overlap while memory
// stays at about two inputs and two outputs.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

namespace artcam::cli {

template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(size_t capacity) : capacity_(capacity) {}

  // False once closed (the consumer stopped): the producer should stop too.
  bool waitForSpace() {
    std::unique_lock lock(mutex_);
    space_.wait(lock, [&] { return closed_ || items_.size() < capacity_; });
    return !closed_;
  }
  void push(T item) {
    {
      const std::lock_guard lock(mutex_);
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
  }
  // The next item, or nothing when the producer finished (close) and the queue is empty.
  std::optional<T> pop() {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return closed_ || !items_.empty(); });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    lock.unlock();
    space_.notify_one();
    return item;
  }
  // No more items will come (producer) or be taken (consumer); wakes both sides.
  void close() {
    {
      const std::lock_guard lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
    space_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_, space_;
  std::deque<T> items_;
  size_t capacity_;
  bool closed_ = false;
};

}  // namespace artcam::cli
