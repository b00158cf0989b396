// SPDX-License-Identifier: Apache-2.0
// A scene plane given by depth at three clicked points. The paper (§3, aerial perspective and
// depth of field) lets the user set scene depth "under the assumption that it is built from
// planar surfaces". Under a pinhole, a world plane's INVERSE depth is affine in the image:
//   1/z(x, y) = a·x + b·y + c                    (x, y: photo pixels, centres at i + 0.5)
// so three points with depths determine it, and it is exact for any plane seen by the photo's
// camera, whatever the focal length. (Depth itself is not affine in the image.)
//
// Bound: a plane made from points gives depths only within the span its own points' depths
// cover, [min depth, max depth]: inside their triangle the inverse depth is a convex
// combination of theirs anyway, and beyond it (the rest of a painted region, its soft fringe)
// it stays at the nearer end of that span instead of extrapolating. Three points set at 3 and
// 8 on a small part of a region would otherwise reach 1/z → 0 (depths of hundreds, or the
// raster's max_depth) a little way past the far point, exactly where a brush's fringe lies,
// and depth of field and haze would peak on the seam. A plane meant to recede further gets a
// point where it should end (docs/architecture.md, "Depth effects follow the painted coverage").
#pragma once

#include "core/model/status.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <limits>

namespace artcam {

struct DepthAnchor {
  Eigen::Vector2d pixel{0.0, 0.0};  // photo pixels
  double depth = 1.0;               // scene depth z > 0, any unit (the user's)
  bool operator==(const DepthAnchor&) const = default;
};

struct InverseDepthPlane {
  double a = 0.0, b = 0.0, c = 0.0;  // 1/z = a·x + b·y + c
  // The inverse depths the plane may give (header: the span of its points); the defaults leave
  // a plane written by hand unbounded. NaN stays NaN (the raster refuses it).
  double min_inverse = -std::numeric_limits<double>::infinity();
  double max_inverse = std::numeric_limits<double>::infinity();

  double inverseDepthAt(double x, double y) const {
    return std::min(std::max(a * x + b * y + c, min_inverse), max_inverse);
  }
};

// Refuses non-finite input, depths <= 0, and three points on (nearly) one line: the triangle's
// area must be at least 1e-6 of its longest side squared (and 0.5 px²), else the plane's tilt
// across that line is unknown. Solved about the centroid for conditioning; bounded to the span
// of the three depths (header).
Result<InverseDepthPlane> planeFromAnchors(const std::array<DepthAnchor, 3>& anchors);

}  // namespace artcam
