// Loading a depth map file as a depth image (depth_raster.h form: 2 channels, (a·z, a)).
//
// - Float files (EXR, float/half TIFF): the first channel's values are depth, times `scale`.
// - Integer files (16-bit PNG/TIFF, also 8-bit): the first channel's STORED integers (no sRGB
//   decoding: depth is not light) times `scale`, e.g. 0.001 for a millimetre PNG read in metres.
// - With `inverse`, the values are inverse depth (disparity-like) and are inverted.
// - Pixels whose value is 0, negative or not finite have no depth (0, 0); they are counted.
// Errors name the file and the cause (missing, unreadable, empty, bad scale).
#pragma once

#include "core/model/image.h"
#include "core/model/status.h"

#include <string>

namespace artcam {

struct DepthMapOptions {
  double scale = 1.0;   // depth units per stored unit
  bool inverse = false; // stored values are 1/z (after scaling)
};

struct DepthMapInfo {
  std::string pixel_type;  // "uint8", "uint16", "half", "float"
  size_t missing = 0;      // pixels without depth
};

Result<ImageF> readDepthMap(const std::string& path, const DepthMapOptions& options = {},
                            DepthMapInfo* info = nullptr);

}  // namespace artcam
