// SPDX-License-Identifier: Apache-2.0
// The gather warp's source positions, stored: for every output pixel, the source point it reads
// (the camera's inverse map), or "no preimage". What `artcam export-map` writes as an ST map.
//
// Conventions: pixel frames, centres at i + 0.5, y down (frames.h). Positions are in SOURCE
// pixels of `source_px`; the camera's tensors are normalised, so any source and output
// resolution of its frames may be asked for. "No preimage" is the coordinate kernels' own
// (inverse.h: beyond a pole curve, folded, Newton failing); a point that maps but lies outside
// the source image IS a preimage, exactly as in the warp.
//
// The positions come from the same coordinate kernels the warp samples through
// (coordinates.h), so a map and a warp can never disagree on where a pixel comes from; only the
// certified cells are switched off by default, because a stored map is a deliverable other
// tools resample, not a preview, and every pixel then passes the one-evaluation check.
#pragma once

#include "core/model/camera.h"
#include "core/mapping/coordinates.h"

#include <string>
#include <vector>

namespace artcam {

struct PositionMapOptions {
  // The warp's defaults except certification (every position checked by one forward
  // evaluation, so each lands within the Newton tolerance of its pixel centre).
  CoordinateOptions coordinates = [] {
    CoordinateOptions c;
    c.certify_tolerance_px = 0.0;
    return c;
  }();
  int threads = 0;  // 0: all cores
};

struct PositionMap {
  FrameSize source_px;               // the frame the positions are in
  FrameSize target_px;               // the map's size: one entry per output pixel, row-major
  std::vector<float> x_px, y_px;     // source position of output pixel (i, j); 0 where invalid
  std::vector<unsigned char> valid;  // 1: has a preimage
  std::string kernel;                // the coordinate kernel used ("homography", "rational", …)
  long long invalid_pixels = 0;

  size_t index(int i, int j) const {
    return static_cast<size_t>(j) * static_cast<size_t>(target_px.width) + static_cast<size_t>(i);
  }
};

// Throws std::invalid_argument for a camera the gather warp refuses (no 2D position block,
// geometry that reads colour or depth); a camera that also changes colour or depth is mapped
// through its position part (attributed.h), since only where pixels go is asked. A camera whose
// denominator is zero everywhere maps nothing (every pixel invalid, kernel "degenerate").
PositionMap sourcePositionMap(const Camera& camera, FrameSize source_px, FrameSize target_px,
                              const PositionMapOptions& options = {});

}  // namespace artcam
