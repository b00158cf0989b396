// SPDX-License-Identifier: Apache-2.0
#include "core/cloud/sample_clouds.h"

#include "core/colour/transfer.h"

#include <stdexcept>

namespace artcam {

Eigen::Vector4f cubeOfCubesColour(int i, int j, int k) {
  const Transfer srgb = Transfer::srgb();
  const auto channel = [&](int v) { return static_cast<float>(srgb.decode(0.15 + 0.425 * v)); };
  return {channel(i), channel(j), channel(k), 1.0f};
}

PointCloud cubeOfCubes(const CubeOfCubesOptions& o) {
  if (o.samples_per_edge < 1 || !(o.half_size > 0) || !(o.gap >= 0 && o.gap < 1))
    throw std::invalid_argument("cubeOfCubes: bad options");
  const int n = o.samples_per_edge;
  const double cell = 2.0 * o.half_size / 3.0;
  const double side = cell * (1.0 - o.gap);
  PointCloud cloud;
  cloud.positions.reserve(static_cast<size_t>(27 * 6 * n * n));
  cloud.colours.reserve(cloud.positions.capacity());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d centre = Eigen::Vector3d(i - 1, j - 1, k - 1) * cell;
        const Eigen::Vector4f colour = cubeOfCubesColour(i, j, k);
        // Each face: an n×n grid at cell centres, so faces and edges do not repeat points.
        for (int axis = 0; axis < 3; ++axis)
          for (const double sign : {-1.0, 1.0})
            for (int a = 0; a < n; ++a)
              for (int b = 0; b < n; ++b) {
                Eigen::Vector3d p;
                p[axis] = sign * side / 2;
                p[(axis + 1) % 3] = ((a + 0.5) / n - 0.5) * side;
                p[(axis + 2) % 3] = ((b + 0.5) / n - 0.5) * side;
                cloud.positions.push_back(centre + p);
                cloud.colours.push_back(colour);
              }
      }
  return cloud;
}

}  // namespace artcam
