// SPDX-License-Identifier: Apache-2.0
// Depth images for the depth block (`(d, 1)`): THE reader of depth and
// disparity map files, for the CLI (artcam warp --depth) and the studio (a map under the
// painted planes, depth_raster.h).
//
// Output: a 1-channel float ImageF of depths, the file's size; 0 means "no depth" (holes: a
// non-positive or non-finite value, zero disparity) — never NaN. Only the first channel is read.
// - Float files (EXR, float/half TIFF): the stored values, as they are (a float file already
//   holds a depth in its own unit; `scale` is for counts).
// - Integer files (16-bit PNG/TIFF, 8-bit): the STORED integer counts, exactly (no sRGB decoding
//   and no [0, 1] normalisation: counts are not light), times `scale` (depth units per count,
//   e.g. 0.001 for a millimetre PNG read in metres). The CLI's --depth-scale, the studio's
//   depth-map scale.
// - Disparity: with baseline_focal > 0 the scaled values are disparities and depth is
//   baseline·focal / disparity; `inverse` is the same with baseline·focal = 1 (values are 1/z).
// Errors are one line naming the file and the cause (missing, not an image, empty, too large,
// bad scale, no usable depth at all).
#pragma once

#include "core/model/image.h"
#include "core/model/status.h"

#include <string>

namespace artcam {

struct DepthFileOptions {
  double scale = 1.0;           // depth units per stored integer count; float files as stored
  bool inverse = false;         // values are inverse depth: baseline_focal 1 unless given
  double baseline_focal = 0.0;  // > 0: values are disparity; depth = baseline_focal / value
};

struct DepthFileSummary {
  std::string pixel_type;  // as stored: "uint8", "uint16", "int8", "int16", "half", "float", …
  int channels = 1;        // in the file; only the first is depth (the caller names the rest)
  long long holes = 0;     // pixels without a usable depth
  double min_depth = 0.0, max_depth = 0.0;  // over the pixels with depth
};

Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options = {},
                             DepthFileSummary* summary = nullptr);

}  // namespace artcam
