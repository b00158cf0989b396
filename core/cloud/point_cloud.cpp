// SPDX-License-Identifier: Apache-2.0
// Cloud statistics. The spacing estimate uses a uniform grid filled by counting sort, which is
// deterministic, linear and needs no per-cell allocations even for millions of points.
#include "core/cloud/point_cloud.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace artcam {

CloudBounds cloudBounds(const PointCloud& cloud) {
  CloudBounds b;
  for (const Eigen::Vector3d& p : cloud.positions) {
    if (!p.allFinite()) continue;
    if (b.empty) {
      b.min = b.max = p;
      b.empty = false;
    } else {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
  }
  return b;
}

double estimatePointSpacing(const PointCloud& cloud, int samples) {
  const CloudBounds bounds = cloudBounds(cloud);
  if (bounds.empty || samples <= 0) return 0.0;
  std::vector<size_t> finite;
  finite.reserve(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i)
    if (cloud.positions[i].allFinite()) finite.push_back(i);
  if (finite.size() < 2) return 0.0;

  // A cell a little larger than the spacing of a volume-filling cloud, and so larger than the
  // spacing of surface or line clouds too: most nearest neighbours lie in the 27 cells around.
  const Eigen::Vector3d extent = bounds.max - bounds.min;
  const double largest = extent.maxCoeff();
  if (largest <= 0.0) return 0.0;
  const double cell = largest / std::max(1.0, std::cbrt(static_cast<double>(finite.size())));
  // A dense grid in compressed rows (counting sort by cell): O(n), no per-cell allocation. The
  // cell is a little larger than the spacing of a volume-filling cloud, and so larger than the
  // spacing of surface or line clouds too: most nearest neighbours lie in the 27 cells around.
  std::array<std::int64_t, 3> dims{};
  for (int k = 0; k < 3; ++k) dims[k] = static_cast<std::int64_t>(std::floor(extent[k] / cell)) + 1;
  const auto cellOf = [&](const Eigen::Vector3d& p) {
    std::array<std::int64_t, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<std::int64_t>(
          static_cast<std::int64_t>(std::floor((p[k] - bounds.min[k]) / cell)), 0, dims[k] - 1);
    return c;
  };
  const auto flat = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<size_t>((x * dims[1] + y) * dims[2] + z);
  };
  std::vector<std::uint32_t> start(static_cast<size_t>(dims[0] * dims[1] * dims[2]) + 1, 0);
  std::vector<std::uint32_t> cell_of(finite.size());
  for (size_t f = 0; f < finite.size(); ++f) {
    const auto c = cellOf(cloud.positions[finite[f]]);
    cell_of[f] = static_cast<std::uint32_t>(flat(c[0], c[1], c[2]));
    ++start[cell_of[f] + 1];
  }
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::uint32_t> members(finite.size());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t f = 0; f < finite.size(); ++f)
      members[fill[cell_of[f]]++] = static_cast<std::uint32_t>(finite[f]);
  }

  const size_t step = std::max<size_t>(1, finite.size() / static_cast<size_t>(samples));
  std::vector<double> nearest;
  for (size_t s = 0; s < finite.size(); s += step) {
    const Eigen::Vector3d& q = cloud.positions[finite[s]];
    const auto c = cellOf(q);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 1; ring <= 4; ++ring) {
      for (std::int64_t x = std::max<std::int64_t>(0, c[0] - ring);
           x <= std::min(dims[0] - 1, c[0] + ring); ++x)
        for (std::int64_t y = std::max<std::int64_t>(0, c[1] - ring);
             y <= std::min(dims[1] - 1, c[1] + ring); ++y)
          for (std::int64_t z = std::max<std::int64_t>(0, c[2] - ring);
               z <= std::min(dims[2] - 1, c[2] + ring); ++z) {
            const size_t id = flat(x, y, z);
            for (std::uint32_t m = start[id]; m < start[id + 1]; ++m) {
              const double d = (cloud.positions[members[m]] - q).norm();
              if (d > 0.0) best = std::min(best, d);  // duplicates are not neighbours
            }
          }
      // Anything outside the searched block is farther than ring·cell.
      if (best <= ring * cell) break;
    }
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return 0.0;
  std::nth_element(nearest.begin(),
                   nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2),
                   nearest.end());
  return nearest[nearest.size() / 2];
}

}  // namespace artcam
