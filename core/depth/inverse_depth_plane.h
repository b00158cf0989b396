// SPDX-License-Identifier: Apache-2.0
// A scene plane given by depth at three clicked points. The paper (§3, aerial perspective and
// depth of field) lets the user set scene depth "under the assumption that it is built from
// planar surfaces". Under a pinhole, a world plane's INVERSE depth is affine in the image:
//   1/z(x, y) = a·x + b·y + c                    (x, y: photo pixels, centres at i + 0.5)
// so three points with depths determine it, and it is exact for any plane seen by the photo's
// camera, whatever the focal length. (Depth itself is not affine in the image.)
#pragma once

#include "core/model/status.h"

#include <Eigen/Core>

#include <array>

namespace artcam {

struct DepthAnchor {
  Eigen::Vector2d pixel{0.0, 0.0};  // photo pixels
  double depth = 1.0;               // scene depth z > 0, any unit (the user's)
  bool operator==(const DepthAnchor&) const = default;
};

struct InverseDepthPlane {
  double a = 0.0, b = 0.0, c = 0.0;  // 1/z = a·x + b·y + c

  double inverseDepthAt(double x, double y) const { return a * x + b * y + c; }
};

// Refuses non-finite input, depths <= 0, and three points on (nearly) one line: the triangle's
// area must be at least 1e-6 of its longest side squared (and 0.5 px²), else the plane's tilt
// across that line is unknown. Solved about the centroid for conditioning.
Result<InverseDepthPlane> planeFromAnchors(const std::array<DepthAnchor, 3>& anchors);

}  // namespace artcam
