// SPDX-License-Identifier: Apache-2.0
// Snapping a click to a calibration-grid corner (the grid matches are clicked, and
// a click snaps to a grid corner where the image has one).
//
// A checkerboard's X-corner is a saddle of the image intensity: the Hessian of the smoothed
// luminance has a strongly negative determinant there. The strongest saddle within the search
// radius is taken, then refined to sub-pixel precision by the classic gradient-orthogonality
// condition (every gradient near a corner is orthogonal to the vector from the corner to its
// pixel; least squares, as in OpenCV's cornerSubPix). Anything that is not clearly a corner —
// flat, an edge, a blob, a refinement that runs away — returns empty, and the click stays where
// it was.
#pragma once

#include "core/model/image.h"

#include <Eigen/Core>

#include <optional>

namespace artcam {

struct CornerSnapOptions {
  double search_radius_px = 8.0;   // where to look for a saddle around the click
  double window_radius_px = 5.0;   // the refinement window (about half a square)
  double smoothing_sigma_px = 1.0;
  // A saddle must reach this share of the strongest saddle a unit-contrast checkerboard
  // corner gives, so texture and noise do not count as corners.
  double min_strength = 0.05;
  // Smallest luminance range (linear, 0–1) in the neighbourhood: below it, noise or texture.
  double min_contrast = 0.05;
};

// Pixel centres at i + 0.5. Colour images use their luminance (alpha ignored).
std::optional<Eigen::Vector2d> snapToGridCorner(const ImageF& image, const Eigen::Vector2d& click_px,
                                                const CornerSnapOptions& options = {});

}  // namespace artcam
