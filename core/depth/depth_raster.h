// SPDX-License-Identifier: Apache-2.0
// Depth planes → a per-pixel depth image (the depth block `(d, 1)`), for the effects
// (depth of field, aerial perspective: the paper's §3) and the studio's overlay.
//
// Output: a 2-channel ImageF, (coverage·z, coverage), alpha_channel = 1: the depth block in
// homogeneous, premultiplied form, like colour (`(a·r, a·g, a·b, a)`). Depth z = ch0 / ch1 where
// ch1 > 0; pixels no plane covers are (0, 0): "no depth", never NaN.
//
// Frames: output pixel (i, j) samples the photo at its centre scaled to the photo's size,
// p = ((i + 0.5)·W/w, (j + 0.5)·H/h) in photo pixels; masks are read at the pixel containing p
// and planes evaluated at p exactly, so a reduced output (the overlay) agrees with the full one.
//
// Compositing: layers in order, later on top, "over" in INVERSE depth with the mask coverage
// as alpha (the plane is affine in inverse depth, so a soft edge blends the two surfaces the
// way a perspective-correct interpolation would). An optional base map (a loaded depth file:
// depth_file.h's 1-channel z with 0 = none, or this 2-channel form; any size: sampled nearest)
// lies under every layer.
//
// A plane from points stays within its points' depth span (inverse_depth_plane.h), so a soft
// fringe beyond them takes the span's end, never an extrapolated spike; a soft edge then blends
// that depth with what lies under it, and the coverage carries the rest (an effect fades with
// it: core/render/depth_coverage.h). Inverse depths below 1/max_depth (a plane written
// unbounded, seen towards its horizon or beyond it, or points beyond max_depth) are clamped to
// it and counted: depth stays finite and positive.
#pragma once

#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "core/model/camera.h"
#include "core/model/image.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace artcam {

// Refers to its mask (a full-resolution mask is a byte per photo pixel: not copied per call);
// the mask must outlive the call.
struct DepthLayer {
  const RegionMask* mask = nullptr;        // photo size
  std::optional<InverseDepthPlane> plane;  // none yet: the layer gives no depth
};

struct DepthRasterOptions {
  int width = 0;  // output size; 0: the photo's (mask) size
  int height = 0;
  double max_depth = 1e4;
  int threads = 0;
  std::function<bool(double)> progress;  // false cancels (as ParallelOptions::progress)
};

struct DepthRasterSummary {
  size_t covered = 0;  // output pixels with coverage > 0
  size_t clamped = 0;  // of those, pixels whose inverse depth was clamped
  double min_depth = 0.0;  // over covered pixels (0 when none)
  double max_depth = 0.0;
  bool cancelled = false;
};

// `photo_width`×`photo_height` is the frame of masks, planes and the base map's scaling.
// Layers whose mask is not that size are a broken contract (std::invalid_argument).
ImageF rasteriseDepth(const std::vector<DepthLayer>& layers, int photo_width, int photo_height,
                      const ImageF* base_map = nullptr, const DepthRasterOptions& options = {},
                      DepthRasterSummary* summary = nullptr);

// Depth at a pixel of a raster (2 channels) or a depth file's image (1 channel), or nothing
// where it has no depth.
std::optional<double> depthAt(const ImageF& depth, int x, int y);

// "" when a depth map of `map`'s size covers a photo of `photo`'s without stretching (the same
// aspect, to a rounding pixel: a map at a lower resolution is sampled as it is, as a sensor's
// depth often is); else the warning every path prints, naming both sizes.
std::string depthMapAspectNote(FrameSize map, FrameSize photo);

}  // namespace artcam
