// SPDX-License-Identifier: Apache-2.0
#include "core/model/piecewise_camera.h"

#include <algorithm>
#include <cmath>

namespace artcam {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

bool PiecewiseCamera::supports(int patch, const Eigen::Vector2d& p) const {
  const std::vector<Eigen::Vector2d>& hull = patches[static_cast<size_t>(patch)].support;
  if (hull.empty()) return true;
  if (hull.size() >= 3) {
    bool inside = true;
    for (size_t i = 0; i < hull.size() && inside; ++i)
      inside = cross(hull[i], hull[(i + 1) % hull.size()], p) >= 0.0;
    if (inside) return true;
  }
  for (size_t i = 0; i < hull.size(); ++i)
    if (distanceToSegment(p, hull[i], hull[(i + 1) % hull.size()]) <= support_margin_px) return true;
  return false;
}

int PiecewiseCamera::patchAt(const Eigen::Vector2d& source_px) const {
  for (size_t i = 0; i < patches.size(); ++i)
    if (patches[i].rect.contains(source_px)) return static_cast<int>(i);
  return -1;
}

std::optional<Eigen::Vector2d> PiecewiseCamera::targetPixelFromSourcePixel(
    const Eigen::Vector2d& source_px) const {
  for (size_t i = 0; i < patches.size(); ++i)
    if (patches[i].rect.contains(source_px) && supports(static_cast<int>(i), source_px))
      return artcam::targetPixelFromSourcePixel(patches[i].camera, source_px);
  return std::nullopt;
}

}  // namespace artcam
