// SPDX-License-Identifier: Apache-2.0
#include "app/cli/progress.h"
#include "app/cli/terminal_text.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace artcam::cli {
namespace {

std::string clock(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

ProgressBar::ProgressBar(int items, bool quiet)
    : items_(items), quiet_(quiet), terminal_(!quiet && ::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  const std::lock_guard lock(mutex_);
  clearLocked();
}

void ProgressBar::stage(const std::string& name, double fraction) {
  const std::lock_guard lock(mutex_);
  const bool changed = name != stage_;
  stage_ = name;
  fraction_known_ = fraction >= 0.0;
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  redrawLocked(changed);
}

void ProgressBar::itemFraction(double fraction) {
  const std::lock_guard lock(mutex_);
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  redrawLocked(false);
}

void ProgressBar::itemDone(double megapixels, const std::string& line) {
  const std::lock_guard lock(mutex_);
  ++done_;
  megapixels_ += megapixels;
  fraction_ = 0.0;
  if (!terminal_ && !quiet_ && !line.empty()) std::fprintf(stderr, "%s\n", line.c_str());
  redrawLocked(true);
}

void ProgressBar::error(const std::string& line) {
  const std::lock_guard lock(mutex_);
  clearLocked();
  std::fprintf(stderr, "%s\n", line.c_str());
  redrawLocked(true);
}

void ProgressBar::finish() {
  const std::lock_guard lock(mutex_);
  clearLocked();
  finished_ = true;
}

void ProgressBar::clearLocked() {
  if (!drawn_) return;
  std::fputs("\r\033[K", terminalControlStream());
  drawn_ = false;
}

void ProgressBar::redrawLocked(bool force) {
  if (!terminal_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double whole = items_ > 0 ? (done_ + fraction_) / items_ : fraction_;
  constexpr int kWidth = 24;
  const int filled = std::clamp(static_cast<int>(whole * kWidth), 0, kWidth);
  std::string bar = "[" + std::string(static_cast<size_t>(filled), '#') +
                    std::string(static_cast<size_t>(kWidth - filled), '-') + "]";
  char text[160];
  if (items_ > 0) {
    const double rate = elapsed > 0 ? megapixels_ / elapsed : 0.0;
    const std::string eta = whole > 0 ? clock(elapsed / whole * (1.0 - whole)) : "?";
    std::snprintf(text, sizeof text, "%s %d/%d files  %.1f Mpix/s  ETA %s", bar.c_str(), done_,
                  items_, rate, eta.c_str());
  } else if (fraction_known_) {
    std::snprintf(text, sizeof text, "%s %s %3.0f%%", bar.c_str(), stage_.c_str(), 100.0 * whole);
  } else {
    std::snprintf(text, sizeof text, "%s %s", bar.c_str(), stage_.c_str());
  }
  // The line's own control sequence raw; its text (a stage, names) as any other.
  std::fputs("\r\033[K", terminalControlStream());
  std::fputs(text, stderr);
  std::fflush(stderr);
  drawn_ = true;
}

namespace {

struct JobInterrupted : std::runtime_error {
  JobInterrupted() : std::runtime_error("interrupted") {}
};

}  // namespace

void JobStages::check() {
  if (interruptRequested()) throw JobInterrupted();
}

void JobStages::stage(const std::string& name) {
  // Leave cooperative mode first: a signal from here on exits at once (nothing polls), one
  // that came before is seen by check().
  cooperative_.reset();
  check();
  bar_.stage(name, -1.0);
}

std::function<bool(double)> JobStages::polled(const std::string& name) {
  cooperative_.emplace();
  check();
  bar_.stage(name, 0.0);
  return cancelOnInterrupt([this, name](double done) { bar_.stage(name, done); });
}

void JobStages::finish() {
  // Every output is in place: a signal after the last poll changes nothing, so no check.
  cooperative_.reset();
  bar_.finish();
}

int runJobStages(const char* command, bool quiet, const std::function<int(JobStages&)>& body) {
  try {
    JobStages job(quiet);
    return body(job);
  } catch (const std::exception&) {
    if (!interruptRequested()) throw;
  }
  std::fprintf(stderr, "artcam %s: interrupted; unfinished outputs not written\n", command);
  return interruptExitCode();
}

}  // namespace artcam::cli
