// SPDX-License-Identifier: Apache-2.0
// A warp of a photo too big to hold whole: decoded, rendered and encoded in bands of rows, with
// only a window of the photo's rows in memory. What `artcam warp` and `batch` do when the photo
// and its output would not fit the memory budget together (core/util/memory_budget.h).
//
// The plan: the camera's positions for every band of output rows are run once (BandWarp,
// core/render/warp.h), giving the source rows each band reads. Rows are decoded top to bottom;
// a row stays in the window until no later band reads it. The largest window the plan needs is
// known before any pixel is decoded, so a camera that reads the photo out of order (turned
// upside down, a strong rotation) is refused up front, naming the memory it would need, rather
// than failing halfway.
//
// The output is what the in-memory warp writes (the same kernel, positions and samples, so
// the same bytes), with one difference: the in-memory warp drops the alpha it adds when every
// pixel turns out opaque, which is known only after the render; streamed, that alpha is dropped
// only when every pixel's position is certainly inside the photo (the plan's positions, 2.5 px
// from its edges), else kept.
#pragma once

#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/model/artcam.h"
#include "core/pipeline/render.h"

#include <cstddef>
#include <string>

namespace artcam {

struct StreamedWarpOptions {
  // Output size (0×0: the output-frame rule, render.h), filter, threads; warp.progress gets the
  // fraction of output rows written and may cancel. Antialias is not taken.
  WarpOptions warp;
  WriteImageOptions write;  // as writeStoredImage takes them; its progress is set here
  double memory_budget_bytes = 0.0;  // what the window and bands may hold; 0: memoryBudgetBytes()
};

struct StreamedWarpSummary {
  FrameSize size;
  std::string kernel;                // "homography", "rational", …
  long long transparent_pixels = 0;
  int window_rows = 0;               // the most photo rows held at once
  double held_bytes = 0.0;           // window + output band + decode chunk
  double ms = 0.0;                   // plan, decode, render and encode
  bool cancelled = false;
  std::string warning;               // the output-frame rule's, if any
  std::string describe() const;      // "streamed gather warp (rational), 812 of 4000 rows held, …"
};

// Whether `camera` can be warped this way: the gather warp of one position camera
// (rendersByGatherWarp).
bool streamableCamera(const Artcam& camera);

// Warps the photo `reader` has opened (no row read yet) through `camera` into `output`, whose
// format must keep the photo's samples (storedWriteKeepsEncoding). Fails in one line naming the
// file and the cause: a camera that is not streamable, a window beyond the budget, a decode or
// encode error, a cancel. No output file is left on failure (atomic save).
Status streamWarp(StoredImageReader& reader, const Artcam& camera, const std::string& output,
                  const StreamedWarpOptions& options, StreamedWarpSummary* summary = nullptr);

}  // namespace artcam
