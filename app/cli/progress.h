// Progress of long CLI jobs on stderr (issue 9, "every long CLI job shows progress").
// On a terminal: one line redrawn in place at most 10 times a second,
//   [##########----------]  12/40 files  38.2 Mpix/s  ETA 0:42
// (a single job shows its stage and percentage instead of files). Not a terminal (a log, a
// pipe, a test): no bar, one plain line per finished item. Quiet: nothing but errors.
// Thread-safe: the batch's decode, render and encode threads all report here.
#pragma once

#include <chrono>
#include <mutex>
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
  // Stage name of a single job ("reading", "warping", "writing") and its fraction done.
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
  std::string stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
  bool drawn_ = false;
  bool finished_ = false;
};

}  // namespace artcam::cli
