// SPDX-License-Identifier: Apache-2.0
// A camera value's inverse maps: for every output pixel, the source position `artcam warp`
// samples, for every kind of camera that warps a photo. What `artcam export-map` writes.
//
// Conventions: position_map.h (source pixels of the camera's source frame, centres at i + 0.5,
// y down, and the Preimage rule for pixels the warp leaves transparent). One map per way the
// photo is moved, each from the renderer the warp itself runs, so a map reproduces the warp:
//   position camera (one layer)  one map, from the coordinate kernels (position_map.h)
//   piecewise                    one map of the mesh (piecewisePositionMap): the render's own
//                                step and rasterised positions, not the patches' inverses
//   per-channel (chromatic aberration, Fig 4: channelCameras)
//                                one map per colour channel, named "R", "G", "B"; the warp's
//                                alpha is the least coverage of the three (warp.h)
//   attributed (one layer with colour, depth or second-colour blocks that change them, or a
//   depth-of-field camera)       one map of its position part, and `left_out` names what the
//                                map does not carry: an ST map moves pixels, it cannot grade
//                                them, so a compositor gets the distortion and is told the rest
// Refused, with the reason: cameras whose positions read colour or depth (eq 8/9: where a pixel
// comes from depends on the photo), 3D cameras, and other layered cameras (layers that change
// colour and are summed, eq 5: no map per layer says how they add up).
#pragma once

#include "core/model/artcam.h"
#include "core/model/status.h"
#include "core/render/position_map.h"

#include <string>
#include <vector>

namespace artcam {

// The most map pixels (all layers together) a caller asks for: the maps are held whole before
// they are written (9 bytes a pixel a layer), so 2^27 (e.g. 16384x8192) is about 1.2 GB, past
// any plate a compositor warps.
inline constexpr long long kMaxSourceMapPixels = 1LL << 27;

struct SourceMapsOptions {
  // The photo the maps will warp, in its pixels; empty: the camera's source frame. The camera is
  // normalised, so only the half-pixel border of what reads the photo (position_map.h) and a
  // piecewise camera's mesh step depend on it: a warp of a photo of this size reads exactly these
  // positions.
  FrameSize source_px;
  PositionMapOptions positions;
  double mesh_step_px = 0.0;  // piecewise cameras: the render's RenderOptions::mesh_step_px
  int threads = 0;            // 0: all cores
};

struct SourceMapLayer {
  std::string name;  // "" for a camera with one map; the colour channel ("R", "G", "B")
  PositionMap map;
};

struct SourceMaps {
  std::vector<SourceMapLayer> layers;
  std::string kernel;                 // e.g. "rational", "piecewise mesh", "per-channel …"
  std::vector<std::string> left_out;  // what the camera does that no map carries, one phrase each
  // Pixels the warp leaves transparent: those where some layer's map reads nothing (the warp's
  // alpha is the least of the layers').
  long long transparentPixels() const;
};

// The maps of `camera` for a `target_px` output, positions in pixels of options.source_px (the
// camera's source frame by default). Failure: one line naming the cause.
Result<SourceMaps> sourceMaps(const Artcam& camera, FrameSize target_px,
                              const SourceMapsOptions& options = {});

}  // namespace artcam
