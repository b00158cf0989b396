// SPDX-License-Identifier: Apache-2.0
// Poles: the denominator x Q_n xᵀ of an image camera must keep one sign over the
// whole source frame, or the map runs to infinity between the pixels. The denominator is a
// quadratic polynomial in (u, v), so its extremes over the frame rectangle are found exactly
// among the corners, the vertex of each edge's 1D quadratic and the interior critical point:
// no sampling, no point missed between samples.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <string>

namespace artcam {

struct PoleCheck {
  bool checked = true;  // false: the camera is not one the check applies to
  bool pole_free = true;
  // min |denominator| over the frame divided by max |denominator|: how far from a pole the
  // camera stays (0 at a pole; 1 for a constant denominator, as with affine maps).
  double margin = 1.0;
  Eigen::Vector2d worst_pixel = Eigen::Vector2d::Zero();  // where |denominator| is smallest
  std::string describe() const;
};

// The denominator's range over the rectangle [lo, hi] of normalised source coordinates.
PoleCheck checkDenominator(const Eigen::Matrix3d& q_denominator, const Eigen::Vector2d& lo,
                           const Eigen::Vector2d& hi);
// The check over the camera's whole source frame, for single-stage 2D position cameras.
PoleCheck checkPoles(const Camera& camera);

}  // namespace artcam
