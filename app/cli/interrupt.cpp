// SPDX-License-Identifier: Apache-2.0
#include "app/cli/interrupt.h"

#include "core/io/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <utility>

namespace artcam::cli {
namespace {

// Lock-free atomics only: the handler may run on any thread, at any point.
std::atomic<int> g_signal{0};
std::atomic<int> g_cooperative{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onInterrupt(int signal_number) {
  const int previous = g_signal.exchange(signal_number);
  if (previous == 0 && g_cooperative.load() > 0) return;  // the command stops at its next poll
  removeLiveTemporaries();
  static const char kMessage[] = "\nartcam: interrupted; unfinished outputs removed\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  ::_exit(128 + signal_number);
}

}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  // Restart interrupted reads and writes: a cooperative command must not see EINTR as an I/O
  // error of the file it is decoding.
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

CooperativeInterrupt::CooperativeInterrupt() { g_cooperative.fetch_add(1); }
CooperativeInterrupt::~CooperativeInterrupt() { g_cooperative.fetch_sub(1); }

bool interruptRequested() { return g_signal.load() != 0; }

int interruptExitCode() {
  const int s = g_signal.load();
  return s != 0 ? 128 + s : 1;
}

std::function<bool(double)> cancelOnInterrupt(std::function<void(double)> report) {
  return [report = std::move(report)](double done) {
    if (report) report(done);
    return !interruptRequested();
  };
}

}  // namespace artcam::cli
