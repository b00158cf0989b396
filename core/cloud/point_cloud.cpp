// Cloud statistics. The spacing estimate uses a sorted uniform grid (cell keys sorted once),
// which is deterministic and needs no per-cell allocations even for millions of points.
#include "core/cloud/point_cloud.h"

#include <algorithm>
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

namespace {

using Key = std::uint64_t;
constexpr int kBits = 21;  // 2^21 cells per axis at most

Key cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return (static_cast<Key>(x) << (2 * kBits)) | (static_cast<Key>(y) << kBits) |
         static_cast<Key>(z);
}

}  // namespace

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
  const std::int64_t limit = (std::int64_t{1} << kBits) - 1;
  const auto cellOf = [&](const Eigen::Vector3d& p) {
    Eigen::Matrix<std::int64_t, 3, 1> c;
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<std::int64_t>(
          static_cast<std::int64_t>(std::floor((p[k] - bounds.min[k]) / cell)), 0, limit);
    return c;
  };

  std::vector<std::pair<Key, std::uint32_t>> grid;
  grid.reserve(finite.size());
  for (const size_t i : finite) {
    const auto c = cellOf(cloud.positions[i]);
    grid.emplace_back(cellKey(c[0], c[1], c[2]), static_cast<std::uint32_t>(i));
  }
  std::sort(grid.begin(), grid.end());

  const size_t step = std::max<size_t>(1, finite.size() / static_cast<size_t>(samples));
  std::vector<double> nearest;
  for (size_t s = 0; s < finite.size(); s += step) {
    const Eigen::Vector3d& q = cloud.positions[finite[s]];
    const auto c = cellOf(q);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 1; ring <= 4; ++ring) {
      for (std::int64_t dx = -ring; dx <= ring; ++dx)
        for (std::int64_t dy = -ring; dy <= ring; ++dy)
          for (std::int64_t dz = -ring; dz <= ring; ++dz) {
            const std::int64_t x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
            if (x < 0 || y < 0 || z < 0 || x > limit || y > limit || z > limit) continue;
            const Key key = cellKey(x, y, z);
            auto it =
                std::lower_bound(grid.begin(), grid.end(), std::make_pair(key, std::uint32_t{0}));
            for (; it != grid.end() && it->first == key; ++it) {
              const double d = (cloud.positions[it->second] - q).norm();
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
