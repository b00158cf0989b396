// SPDX-License-Identifier: Apache-2.0
// The gather warp's source positions, stored: for every output pixel, the source point it reads
// (the camera's inverse map), or "no preimage". What `artcam export-map` writes as an ST map.
//
// Conventions: pixel frames, centres at i + 0.5, y down (frames.h). Positions are in SOURCE
// pixels of `source_px`; the camera's tensors are normalised, so any source and output
// resolution of its frames may be asked for. "No preimage" is the coordinate kernels' own
// (inverse.h: beyond a pole curve, folded, Newton failing).
//
// What a pixel reads (the one rule `warp`, `export-map` and `fit --stmap` share; docs/
// architecture.md, "Pixels without a preimage, and ST maps"): a pixel is transparent in the
// warp exactly when it has no preimage or its preimage lies so far outside the photo that the
// warp's (default, bilinear) filter has no tap inside: x − ½ ∉ (−1, W) or y − ½ ∉ (−1, H), the span
// sampler's own test in its own float arithmetic. Such a pixel is Preimage::OutsidePhoto: its
// position is kept (it is still the camera's geometry, which fit --stmap fits), but a map says
// it reads nothing (alpha 0), so a compositor that clamps at the border cannot smear the edge
// into it.
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

enum class Preimage : unsigned char {
  None = 0,          // no preimage: the warp leaves the pixel transparent
  InPhoto = 1,       // the warp's bilinear filter reads the photo there (alpha > 0)
  OutsidePhoto = 2,  // a preimage beyond the filter's reach of the photo: transparent too
};

// The rule above for a preimage at (x_px, y_px) of a `source_px` photo.
inline Preimage preimageAt(float x_px, float y_px, FrameSize source_px) {
  const float fx = x_px - 0.5f, fy = y_px - 0.5f;
  return fx > -1.0f && fx < static_cast<float>(source_px.width) && fy > -1.0f &&
                 fy < static_cast<float>(source_px.height)
             ? Preimage::InPhoto
             : Preimage::OutsidePhoto;
}

struct PositionMap {
  FrameSize source_px;               // the frame the positions are in
  FrameSize target_px;               // the map's size: one entry per output pixel, row-major
  std::vector<float> x_px, y_px;     // source position of output pixel (i, j); 0 where None
  std::vector<Preimage> preimage;    // what the pixel reads
  std::string kernel;                // the coordinate kernel used ("homography", "rational", …)
  long long invalid_pixels = 0;      // Preimage::None
  long long outside_pixels = 0;      // Preimage::OutsidePhoto
  // The pixels the warp leaves transparent (alpha 0 in an STMap).
  long long transparentPixels() const { return invalid_pixels + outside_pixels; }

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

// An empty map of the given frames (every pixel Preimage::None), for other renderers' positions
// (the piecewise mesh), and the classification of one computed position into it.
PositionMap emptyPositionMap(FrameSize source_px, FrameSize target_px);
// Stores (x_px, y_px) at index k by the rule above. Not thread-safe for the counters: callers
// that fill rows in parallel count with countPreimages() afterwards.
inline void storePreimage(PositionMap& map, size_t k, float x_px, float y_px) {
  map.x_px[k] = x_px;
  map.y_px[k] = y_px;
  map.preimage[k] = preimageAt(x_px, y_px, map.source_px);
}
// Sets invalid_pixels and outside_pixels from `preimage`.
void countPreimages(PositionMap& map);

}  // namespace artcam
