// SPDX-License-Identifier: Apache-2.0
// Progress of long CLI jobs on stderr: every long CLI job shows progress.
// On a terminal: one line redrawn in place at most 10 times a second,
//   [##########----------]  12/40 files  38.2 Mpix/s  ETA 0:42
// (a single job shows its stage and percentage instead of files). Not a terminal (a log, a
// pipe, a test): no bar, one plain line per finished item. Quiet: nothing but errors.
// Thread-safe: the batch's decode, render and encode threads all report here.
#pragma once

#include "app/cli/interrupt.h"

#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace artcam::cli {

class ProgressBar {
 public:
  // `items` = files in a batch (0: a single job whose fraction is shown as a percentage).
  ProgressBar(int items, bool quiet);
  ~ProgressBar();  // clears the bar line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool onTerminal() const { return terminal_; }
  // Stage name of a single job ("reading", "warping", "writing") and its fraction done; a
  // negative fraction: not known (a core function without a progress hook), no percentage.
  void stage(const std::string& name, double fraction);
  // Fraction of the item now being rendered (counts towards the ETA).
  void itemFraction(double fraction);
  // An item finished: `line` is printed when not on a terminal (and not quiet).
  void itemDone(double megapixels, const std::string& line);
  // An error line, always printed (above the bar on a terminal).
  void error(const std::string& line);
  // Clears the bar for good (before the job's own last lines on stdout).
  void finish();

 private:
  void redrawLocked(bool force);
  void clearLocked();

  std::mutex mutex_;
  const int items_;
  const bool quiet_;
  const bool terminal_;
  int done_ = 0;
  double megapixels_ = 0.0;
  double fraction_ = 0.0;
  bool fraction_known_ = true;
  std::string stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
  bool drawn_ = false;
  bool finished_ = false;
};

// The stages of a single long job that is not a warp (render, insert, sample, fit). Ctrl-C:
// during a `polled` stage, whose core function takes a progress hook, the signal only raises
// the flag and the hook cancels (interrupt.h's cooperative mode; the atomic writer removes its
// temporary); during a plain `stage` (core offers no hook: ray tracing, fitting, PLY and CSV
// I/O) the default handler exits at once and removes the temporaries of saves in flight.
class JobStages {
 public:
  explicit JobStages(bool quiet) : bar_(0, quiet) {}
  // A stage without a hook (shown without a percentage). Throws once a signal came.
  void stage(const std::string& name);
  // A stage whose core function polls: the progress callback to hand it. Throws once a
  // signal came.
  std::function<bool(double)> polled(const std::string& name);
  // Throws once a signal came (after a polled core call that returned early).
  void check();
  // Clears the bar before the command's own lines on stdout (all outputs written).
  void finish();

 private:
  ProgressBar bar_;
  std::optional<CooperativeInterrupt> cooperative_;
};

// Runs a single job's body. Once Ctrl-C or kill came, whatever the body threw is the
// cancellation (a reader or writer failing with "cancelled", or JobStages' own check):
// prints "artcam COMMAND: interrupted; unfinished outputs not written" and returns
// interruptExitCode().
int runJobStages(const char* command, bool quiet, const std::function<int(JobStages&)>& body);

}  // namespace artcam::cli
