// Depth images for the depth block (DESIGN §1 `(d, 1)`; issue 6 item 4): read a depth or
// disparity map into a 1-channel float ImageF of depths.
//
// - Float files (EXR, float TIFF): values are depths as stored (no transfer curve).
// - Integer files (16-bit PNG/TIFF, 8-bit): the stored integer counts times `scale`
//   (e.g. 0.001 for millimetres → metres). No sRGB decoding: counts are not light.
// - Disparity: with baseline_focal > 0 the (scaled) values are disparities and depth is
//   baseline·focal / disparity.
// Pixels with a non-positive or non-finite depth (holes, zero disparity) become 0, which the
// renderers treat as "no depth" — never NaN. Only the first channel is read.
#pragma once

#include "core/model/image.h"
#include "core/model/status.h"

#include <string>

namespace artcam {

struct DepthFileOptions {
  double scale = 1.0;           // per integer count; ignored for float files
  double baseline_focal = 0.0;  // > 0: the file holds disparity (same unit as scale gives)
};

struct DepthFileSummary {
  long long holes = 0;  // pixels without a usable depth
  double min_depth = 0.0, max_depth = 0.0;
};

// Errors name the file and the cause ("d.png: cannot open: …", "… has 0 channels").
Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options = {},
                             DepthFileSummary* summary = nullptr);

}  // namespace artcam
