// SPDX-License-Identifier: Apache-2.0
// Chromatic aberration, both ways of the paper's Fig 4 (§3), as layered image cameras
// (attributed.h renderLayers: one camera per colour layer, colours summed).
//
// Block layout of every layer: position (u, v, 1) in the normalised frame (frames.h), then
// colour (a·r, a·g, a·b, a). Each layer's cc part keeps its own channel and alpha and zeroes
// the other two, so the three layers add up to one picture.
//
// - rgbShiftLayers: the "mis-printing" made from three RTcams (Fig 4, middle). Layer k scales
//   positions about the frame centre by (1 + scale_k) and shifts them by (dx_k, dy_k): a pure
//   pp map (gather path), the same for every pixel of that layer.
// - colourShiftLayers: the ARTcam that moves each pixel by its own colour (eq 8/9, Fig 4,
//   right): Q_1pc has s_k at (1, k) and 1 at (1, 4), Q_2pc the same in its second row, and the
//   position's homogeneous output is p3·c4, so y = (p1, p2)·(s_k·c_k + c4)/(p3·c4)
//   = p·(1 + s_k·r_k) with r_k the unpremultiplied channel: bright red expands for s_red > 0.
//   The geometry depends on colour (splat path). Stored symmetrically, every coupling is built
//   with symmetricOuter, which halves the off-diagonal blocks (eq 10).
#pragma once

#include "core/model/camera.h"

#include <array>
#include <vector>

namespace artcam {

struct RgbShiftParams {
  std::array<double, 3> scale = {0.006, 0.0, -0.006};  // radial, per channel (r, g, b)
  std::array<double, 3> dx = {0, 0, 0};  // shift, normalised units (half the larger side = 1)
  std::array<double, 3> dy = {0, 0, 0};
};
std::vector<Camera> rgbShiftLayers(const RgbShiftParams& p, FrameSize source, FrameSize target);

struct ColourShiftParams {
  std::array<double, 3> s = {0.05, 0.0, -0.03};  // s_red, s_green, s_blue (eq 8/9)
};
std::vector<Camera> colourShiftLayers(const ColourShiftParams& p, FrameSize source,
                                      FrameSize target);

// Element indices of the [position 3 | colour 4] layout used above.
namespace layout_pc {
inline constexpr int kU = 0, kV = 1, kW = 2, kR = 3, kG = 4, kB = 5, kA = 6, kN = 7;
}

}  // namespace artcam
