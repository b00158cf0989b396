// SPDX-License-Identifier: Apache-2.0
#include "core/depth/inverse_depth_plane.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace artcam {

Result<InverseDepthPlane> planeFromAnchors(const std::array<DepthAnchor, 3>& anchors) {
  for (size_t i = 0; i < 3; ++i) {
    const DepthAnchor& k = anchors[i];
    const std::string which = "depth point " + std::to_string(i + 1);
    if (!k.pixel.allFinite() || !std::isfinite(k.depth))
      return Result<InverseDepthPlane>::failure(which + " is not a finite number");
    if (k.depth <= 0.0)
      return Result<InverseDepthPlane>::failure(which + ": depth must be greater than 0");
  }
  const Eigen::Vector2d centroid = (anchors[0].pixel + anchors[1].pixel + anchors[2].pixel) / 3.0;
  const Eigen::Vector2d e1 = anchors[1].pixel - anchors[0].pixel;
  const Eigen::Vector2d e2 = anchors[2].pixel - anchors[0].pixel;
  const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
  const double longest = std::max({e1.norm(), e2.norm(), (anchors[2].pixel - anchors[1].pixel).norm()});
  if (area < 0.5 || area < 1e-6 * longest * longest)
    return Result<InverseDepthPlane>::failure(
        "the three depth points lie on one line: move one of them off it");
  Eigen::Matrix3d m;
  Eigen::Vector3d rhs;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d p = anchors[static_cast<size_t>(i)].pixel - centroid;
    m.row(i) << p.x(), p.y(), 1.0;
    rhs(i) = 1.0 / anchors[static_cast<size_t>(i)].depth;
  }
  const Eigen::Vector3d s = m.partialPivLu().solve(rhs);
  InverseDepthPlane plane;
  plane.a = s(0);
  plane.b = s(1);
  plane.c = s(2) - s(0) * centroid.x() - s(1) * centroid.y();
  // The span of the points' own depths (inverse_depth_plane.h): no extrapolation past them.
  const auto [nearest, farthest] = std::minmax(
      {anchors[0].depth, anchors[1].depth, anchors[2].depth});
  plane.min_inverse = 1.0 / farthest;
  plane.max_inverse = 1.0 / nearest;
  return Result<InverseDepthPlane>::success(plane);
}

}  // namespace artcam
