// SPDX-License-Identifier: Apache-2.0
#include "core/model/piecewise_camera.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

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

std::optional<Eigen::Vector2d> PiecewiseCamera::patchPixelFromSourcePixel(const Eigen::Vector2d& source_px) const {
  if (!patch_frame) return source_px;
  const Eigen::Vector3d y = patch_frame->patch_from_source * source_px.homogeneous();
  if (!(y.z() > 0.0)) return std::nullopt;
  const Eigen::Vector2d p = y.hnormalized();
  if (!p.allFinite()) return std::nullopt;
  return p;
}

std::optional<Eigen::Vector2d> PiecewiseCamera::sourcePixelFromPatchPixel(const Eigen::Vector2d& patch_px) const {
  if (!patch_frame) return patch_px;
  // x = H⁻¹ (p, 1) has H x = (p, 1), of weight 1: the source point x / x_w is on the source's
  // side of the pole line (its image has a positive weight) exactly when x_w > 0.
  const Eigen::Matrix3d& h = patch_frame->patch_from_source;
  const double det = h.determinant();
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return std::nullopt;
  const Eigen::Vector3d x = h.inverse() * patch_px.homogeneous();
  if (!(x.z() > 0.0)) return std::nullopt;
  const Eigen::Vector2d s = x.hnormalized();
  if (!s.allFinite()) return std::nullopt;
  return s;
}

PatchRect PiecewiseCamera::sourceBox(int patch) const {
  const PatchRect& r = patches[static_cast<size_t>(patch)].rect;
  if (!patch_frame) return r;
  const PatchRect whole{0.0, 0.0, static_cast<double>(source_size.width), static_cast<double>(source_size.height)};
  PatchRect box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(r.x0, r.y0), Eigen::Vector2d(r.x1, r.y0),
                                        Eigen::Vector2d(r.x0, r.y1), Eigen::Vector2d(r.x1, r.y1)}) {
    const auto s = sourcePixelFromPatchPixel(corner);
    if (!s) return whole;  // the rectangle reaches the pole line: its preimage is unbounded
    box.x0 = std::min(box.x0, s->x()), box.y0 = std::min(box.y0, s->y());
    box.x1 = std::max(box.x1, s->x()), box.y1 = std::max(box.y1, s->y());
  }
  // A homography maps a convex region not crossing its pole line onto a convex region, so the
  // corners' box holds the whole preimage.
  box.x0 = std::max(box.x0, whole.x0), box.y0 = std::max(box.y0, whole.y0);
  box.x1 = std::min(box.x1, whole.x1), box.y1 = std::min(box.y1, whole.y1);
  return box;
}

int PiecewiseCamera::patchAt(const Eigen::Vector2d& source_px) const {
  const auto p = patchPixelFromSourcePixel(source_px);
  if (!p) return -1;
  for (size_t i = 0; i < patches.size(); ++i)
    if (patches[i].rect.contains(*p)) return static_cast<int>(i);
  return -1;
}

std::optional<Eigen::Vector2d> PiecewiseCamera::targetPixelFromSourcePixel(
    const Eigen::Vector2d& source_px) const {
  const auto p = patchPixelFromSourcePixel(source_px);
  if (!p) return std::nullopt;
  for (size_t i = 0; i < patches.size(); ++i)
    if (patches[i].rect.contains(*p) && supports(static_cast<int>(i), *p))
      return artcam::targetPixelFromSourcePixel(patches[i].camera, source_px);
  return std::nullopt;
}

bool convexInteriorsApart(const std::vector<Eigen::Vector2d>& a,
                          const std::vector<Eigen::Vector2d>& b, double gap) {
  if (a.size() < 3 || b.size() < 3) return false;
  double size = 0.0;
  for (const auto* poly : {&a, &b})
    for (const Eigen::Vector2d& p : *poly) size = std::max(size, p.cwiseAbs().maxCoeff());
  const double tolerance = 1e-9 * std::max(size, 1.0);
  for (const auto* poly : {&a, &b})
    for (size_t i = 0; i < poly->size(); ++i) {
      const Eigen::Vector2d e = (*poly)[(i + 1) % poly->size()] - (*poly)[i];
      if (e.norm() <= tolerance) continue;
      const Eigen::Vector2d axis = Eigen::Vector2d(-e.y(), e.x()).normalized();
      double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
      for (const Eigen::Vector2d& p : a)
        a0 = std::min(a0, axis.dot(p)), a1 = std::max(a1, axis.dot(p));
      for (const Eigen::Vector2d& p : b)
        b0 = std::min(b0, axis.dot(p)), b1 = std::max(b1, axis.dot(p));
      if (a1 + gap <= b0 + tolerance || b1 + gap <= a0 + tolerance) return true;
    }
  return false;
}

}  // namespace artcam
