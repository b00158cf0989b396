// SPDX-License-Identifier: Apache-2.0
#include "core/depth/edge_aware_brush.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace artcam {

Eigen::Vector3f photoColourAt(const ImageF& photo, int x, int y) {
  const float* p = photo.pixel(x, y);
  float c[3] = {0.0f, 0.0f, 0.0f};
  int k = 0;
  for (int ch = 0; ch < photo.channels && k < 3; ++ch)
    if (ch != photo.alpha_channel) c[k++] = p[ch];
  if (k == 1) c[1] = c[2] = c[0];
  return {c[0], c[1], c[2]};
}

DabLimit edgeAwareLimit(const RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& centre,
                        double radius, const EdgeAwareOptions& options) {
  DabLimit limit;
  limit.rect = mask.dabRect(centre, radius);
  const PixelRect& r = limit.rect;
  if (r.empty()) return limit;
  const int w = r.width();
  limit.allowed.assign(static_cast<size_t>(w) * static_cast<size_t>(r.height()), 0);
  const int cx = static_cast<int>(std::floor(centre.x()));
  const int cy = static_cast<int>(std::floor(centre.y()));
  const double r2 = radius * radius;
  const auto eligible = [&](int x, int y) {
    if (x < r.x0 || y < r.y0 || x >= r.x1 || y >= r.y1) return false;
    const double dx = x + 0.5 - centre.x(), dy = y + 0.5 - centre.y();
    if (dx * dx + dy * dy > r2) return false;
    return (photoColourAt(photo, x, y) - options.reference).norm() <= options.tolerance;
  };
  const auto index = [&](int x, int y) {
    return static_cast<size_t>(y - r.y0) * static_cast<size_t>(w) + static_cast<size_t>(x - r.x0);
  };
  // The centre pixel counts as in the disc even for a radius under half a pixel.
  if (cx < r.x0 || cy < r.y0 || cx >= r.x1 || cy >= r.y1 ||
      (photoColourAt(photo, cx, cy) - options.reference).norm() > options.tolerance)
    return limit;
  std::vector<std::pair<int, int>> stack{{cx, cy}};
  limit.allowed[index(cx, cy)] = 1;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    const int nx[4] = {x + 1, x - 1, x, x};
    const int ny[4] = {y, y, y + 1, y - 1};
    for (int k = 0; k < 4; ++k)
      if (eligible(nx[k], ny[k]) && !limit.allowed[index(nx[k], ny[k])]) {
        limit.allowed[index(nx[k], ny[k])] = 1;
        stack.emplace_back(nx[k], ny[k]);
      }
  }
  return limit;
}

PixelRect stampEdgeAware(RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& centre,
                         const BrushOptions& brush, const EdgeAwareOptions& options) {
  if (photo.width != mask.width() || photo.height != mask.height())
    throw std::invalid_argument("edge-aware brush: the photo is not the mask's size");
  const DabLimit limit = edgeAwareLimit(mask, photo, centre, brush.radius, options);
  return mask.stamp(centre, brush, &limit);
}

PixelRect segmentEdgeAware(RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& from,
                           const Eigen::Vector2d& to, const BrushOptions& brush,
                           const EdgeAwareOptions& options) {
  if (!from.allFinite() || !to.allFinite()) return {};
  // RegionMask::segment's spacing: every quarter radius, at least every pixel.
  const double spacing = std::max(1.0, 0.25 * brush.radius);
  const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / spacing)));
  PixelRect touched;
  for (int s = 1; s <= steps; ++s)
    touched = touched.united(stampEdgeAware(
        mask, photo, from + (to - from) * (static_cast<double>(s) / steps), brush, options));
  return touched;
}

}  // namespace artcam
