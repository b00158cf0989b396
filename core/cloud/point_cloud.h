// SPDX-License-Identifier: Apache-2.0
// A coloured point cloud in object space (the paper's Fig 1 works on one).
//
// Conventions (docs/architecture.md, "The model"):
// - Positions are object units, (X, Y, Z); the ARTcam position block sees (X, Y, Z, 1).
// - Colours are LINEAR light, PREMULTIPLIED by alpha, like ImageF: the colour block sees
//   (a·r, a·g, a·b, a) as it is stored here. Files hold sRGB-encoded bytes or linear floats
//   (core/io/ply.h converts).
// - A cloud without colour has an empty `colours`; renderers then use opaque white.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace artcam {

struct PointCloud {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector4f> colours;  // empty, or one per position
  bool has_alpha = false;                // the source had an alpha channel (kept on write)

  size_t size() const { return positions.size(); }
  bool hasColour() const { return !colours.empty(); }
  // Opaque white when the cloud has no colour.
  Eigen::Vector4f colour(size_t i) const {
    return colours.empty() ? Eigen::Vector4f(1, 1, 1, 1) : colours[i];
  }
};

struct CloudBounds {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  bool empty = true;

  Eigen::Vector3d centre() const { return 0.5 * (min + max); }
  double radius() const { return empty ? 0.0 : 0.5 * (max - min).norm(); }
};

// Bounds of the finite positions.
CloudBounds cloudBounds(const PointCloud& cloud);

// Typical distance between neighbouring points: the median nearest-neighbour distance over a
// deterministic sample of up to `samples` points (a hash grid keeps it near-linear). Renderers
// size splats from it (core/cloud/cloud_render.h). 0 for fewer than two distinct points.
double estimatePointSpacing(const PointCloud& cloud, int samples = 2000);

}  // namespace artcam
