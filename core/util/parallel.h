// SPDX-License-Identifier: Apache-2.0
// Splitting a render into bands of rows over worker threads, so a render uses every core, with a
// cancel hook polled between bands, after OpenImageIO's parallel_image + cancel callback.
#pragma once

#include <functional>

namespace artcam {

struct ParallelOptions {
  int threads = 0;     // 0: the CPUs this process may use (slotThreadCount, slot_limits.h)
  int band_rows = 16;  // rows per work item
  // Called on the CALLING thread (never on a worker) after bands complete, with the fraction
  // of rows done, at least once (with 1.0 when nothing was cancelled); return false to cancel.
  // Bands already running finish, no new band starts; a false is honoured even after the
  // last band, so a caller that said "stop" never receives a result.
  std::function<bool(double)> progress;
};

// Runs `band(y_begin, y_end)` for consecutive bands covering [0, rows). `band` runs on worker
// threads concurrently and must only write rows it was given. Returns false when cancelled.
// An exception thrown by `band` stops the work and is rethrown here.
bool parallelForRows(int rows, const ParallelOptions& options,
                     const std::function<void(int, int)>& band);

// The thread count `threads` stands for (0: every CPU of the process's slot, at least 1).
int resolveThreadCount(int threads);

}  // namespace artcam
