// SPDX-License-Identifier: Apache-2.0
#include "core/piecewise/unfold_walls.h"

#include "core/fit/fit_image.h"
#include "core/model/piecewise_camera.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace artcam {
namespace {

constexpr int kMinDepthSamples = 50;

bool inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

struct Plane {
  Eigen::Vector3d n;  // unit, towards the camera
  double d = 0.0;     // n·X = d
};

// The wall's plane n·X = d from its depth samples (ray r = ((x − cx)/f, (y − cy)/f, 1), depth z):
// on a plane 1/z = (n·r)/d is linear in the pixel, and stereo's error is in disparity, i.e. in
// 1/z, evenly over the pixels, so the plane is the least-squares fit of 1/z = a·r_x + b·r_y + c
// (normal ∝ (a, b, c), d = 1/|(a, b, c)|), on conditioned coordinates, refitted on the samples
// within 2.5 × the median residual until none is dropped: a bit of roof or lawn inside a rough
// outline, or the matcher's smear at an occluding edge, does not tilt it.
struct DepthSample {
  Eigen::Vector2d r;  // the ray's (x, y) at z = 1
  double w = 0.0;     // 1 / z
};

Plane fitPlane(std::vector<DepthSample> samples, double* rms) {
  Plane plane;
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  for (int round = 0; round < 8; ++round) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& s : samples) mean += s.r;
    mean /= static_cast<double>(samples.size());
    double spread = 0.0;
    for (const auto& s : samples) spread += (s.r - mean).squaredNorm();
    spread = std::sqrt(spread / samples.size()) + 1e-12;
    Eigen::MatrixXd a(samples.size(), 3);
    Eigen::VectorXd b(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      const Eigen::Vector2d q = (samples[i].r - mean) / spread;
      a.row(static_cast<Eigen::Index>(i)) << q.x(), q.y(), 1.0;
      b(static_cast<Eigen::Index>(i)) = samples[i].w;
    }
    const Eigen::Vector3d k = a.colPivHouseholderQr().solve(b);
    // Back from the conditioned coordinates: w = k0 (rx − mx)/s + k1 (ry − my)/s + k2.
    abc = Eigen::Vector3d(k(0) / spread, k(1) / spread,
                          k(2) - (k(0) * mean.x() + k(1) * mean.y()) / spread);
    std::vector<double> residual(samples.size());
    for (size_t i = 0; i < samples.size(); ++i)
      residual[i] = std::abs(abc.x() * samples[i].r.x() + abc.y() * samples[i].r.y() + abc.z() -
                             samples[i].w);
    std::vector<double> sorted = residual;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double keep = 2.5 * std::max(sorted[sorted.size() / 2], 1e-15);
    std::vector<DepthSample> kept;
    for (size_t i = 0; i < samples.size(); ++i)
      if (residual[i] <= keep) kept.push_back(samples[i]);
    const bool done =
        kept.size() == samples.size() || kept.size() < static_cast<size_t>(kMinDepthSamples);
    if (!done) samples = std::move(kept);
    // The samples' distance from the plane, in depth units.
    const double norm = abc.norm();
    plane.n = -abc / norm;  // n·X = d with d < 0: the camera on the normal's side
    plane.d = -1.0 / norm;
    double sum = 0.0;
    for (const auto& s : samples) {
      const Eigen::Vector3d X = Eigen::Vector3d(s.r.x(), s.r.y(), 1.0) / s.w;
      sum += std::pow(plane.n.dot(X) - plane.d, 2);
    }
    *rms = std::sqrt(sum / samples.size());
    if (done) break;
  }
  return plane;
}

std::string named(const WallOutline& w, size_t i) {
  return "wall " + (w.name.empty() ? std::to_string(i + 1) : "\"" + w.name + "\"");
}

}  // namespace

Result<Artcam> unfoldWalls(const ImageF& depth, FrameSize photo,
                           const std::vector<WallOutline>& walls, const UnfoldOptions& options,
                           UnfoldSummary* summary) {
  using R = Result<Artcam>;
  if (!(options.focal_px > 0.0) || !std::isfinite(options.focal_px))
    return R::failure("the focal length must be above 0 pixels");
  if (!(options.px_per_unit >= 0.0) || !std::isfinite(options.px_per_unit))
    return R::failure("the scale must be a number ≥ 0");
  if (depth.empty() || !photo.isImage()) return R::failure("no depth map");
  if (walls.empty()) return R::failure("no walls");
  const Eigen::Vector2d pp = options.principal_px.x() < 0
                                 ? Eigen::Vector2d(0.5 * photo.width, 0.5 * photo.height)
                                 : options.principal_px;
  const double f = options.focal_px;
  auto ray = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector3d((p.x() - pp.x()) / f, (p.y() - pp.y()) / f, 1.0);
  };
  const double sx = static_cast<double>(depth.width) / photo.width;
  const double sy = static_cast<double>(depth.height) / photo.height;

  struct Layout {
    Plane plane;
    Eigen::Vector3d origin, eu, ev;
    double umin, umax, vmin, vmax;
  };
  std::vector<Layout> layouts;
  UnfoldSummary local;
  for (size_t i = 0; i < walls.size(); ++i) {
    const WallOutline& w = walls[i];
    if (w.photo_px.size() < 3)
      return R::failure(named(w, i) + ": an outline needs 3 corners or more");
    for (const Eigen::Vector2d& c : w.photo_px)
      if (c.x() < -1 || c.y() < -1 || c.x() > photo.width + 1 || c.y() > photo.height + 1)
        return R::failure(named(w, i) + ": a corner lies outside the " +
                          std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                          " photo");
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& c : w.photo_px) box.extend(c);
    // Depth is sampled inside the outline shrunk by a tenth towards its centroid: at the
    // outline the stereo matcher smears the nearer surface over the farther one.
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& c : w.photo_px) centroid += c;
    centroid /= static_cast<double>(w.photo_px.size());
    std::vector<Eigen::Vector2d> inner;
    for (const Eigen::Vector2d& c : w.photo_px) inner.push_back(centroid + 0.9 * (c - centroid));
    std::vector<DepthSample> points;
    for (int y = std::max(0, static_cast<int>(box.min().y()));
         y < std::min(photo.height, static_cast<int>(box.max().y()) + 1); ++y)
      for (int x = std::max(0, static_cast<int>(box.min().x()));
           x < std::min(photo.width, static_cast<int>(box.max().x()) + 1); ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        if (!inside(inner, p)) continue;
        const int dx = std::min(depth.width - 1, static_cast<int>(p.x() * sx));
        const int dy = std::min(depth.height - 1, static_cast<int>(p.y() * sy));
        const float z = *depth.pixel(dx, dy);
        if (z > 0.0f && std::isfinite(z)) {
          const Eigen::Vector3d r = ray(p);
          points.push_back({{r.x(), r.y()}, 1.0 / z});
        }
      }
    if (points.size() < static_cast<size_t>(kMinDepthSamples))
      return R::failure(named(w, i) + ": only " + std::to_string(points.size()) +
                        " pixels with depth inside its outline (at least " +
                        std::to_string(kMinDepthSamples) + " fix its plane)");
    UnfoldedWall report;
    report.name = w.name;
    report.depth_samples = static_cast<int>(points.size());
    const Plane plane = fitPlane(points, &report.plane_rms);
    report.normal = plane.n;
    // The corners on the plane.
    std::vector<Eigen::Vector3d> corners;
    for (const Eigen::Vector2d& c : w.photo_px) {
      const Eigen::Vector3d r = ray(c);
      const double along = plane.n.dot(r);
      if (!(along < -1e-6))  // the ray meets the plane behind the camera, or grazes it
        return R::failure(named(w, i) +
                          ": its plane is seen edge-on at a corner (the depth "
                          "inside its outline does not describe a wall)");
      corners.push_back(r * (plane.d / along));
    }
    Layout l;
    l.plane = plane;
    l.origin = corners[0];
    Eigen::Vector3d base = corners[1] - corners[0];
    base -= plane.n * plane.n.dot(base);
    if (base.norm() < 1e-9) return R::failure(named(w, i) + ": its base edge has no length");
    l.eu = base.normalized();
    l.ev = plane.n.cross(l.eu);
    double side = 0.0;
    for (const auto& c : corners) side += l.ev.dot(c - l.origin);
    if (side < 0) l.ev = -l.ev;
    l.umin = l.vmin = std::numeric_limits<double>::infinity();
    l.umax = l.vmax = -std::numeric_limits<double>::infinity();
    for (const auto& c : corners) {
      const double u = l.eu.dot(c - l.origin), v = l.ev.dot(c - l.origin);
      l.umin = std::min(l.umin, u);
      l.umax = std::max(l.umax, u);
      l.vmin = std::min(l.vmin, v);
      l.vmax = std::max(l.vmax, v);
    }
    report.width = l.umax - l.umin;
    report.height = l.vmax - l.vmin;
    layouts.push_back(l);
    local.walls.push_back(report);
  }
  double total_width = 0.0, tallest = 0.0;
  for (const Layout& l : layouts) {
    total_width += l.umax - l.umin;
    tallest = std::max(tallest, l.vmax - l.vmin);
  }
  const double scale = options.px_per_unit > 0 ? options.px_per_unit : photo.width / total_width;
  const FrameSize out{std::max(1, static_cast<int>(std::ceil(scale * total_width))),
                      std::max(1, static_cast<int>(std::ceil(scale * tallest)))};
  if (out.width > kMaxFrameSide || out.height > kMaxFrameSide)
    return R::failure("the unfolded picture would be " + std::to_string(out.width) + "x" +
                      std::to_string(out.height) + ": lower the scale");
  // Seams: walls left to right; a vertical cut halfway between neighbours' facing extremes, so
  // the patches' rectangles tile the photo without overlapping.
  std::vector<double> cut_left(walls.size()), cut_right(walls.size());
  for (size_t i = 0; i < walls.size(); ++i) {
    double lo = photo.width, hi = 0;
    for (const auto& c : walls[i].photo_px) {
      lo = std::min(lo, c.x());
      hi = std::max(hi, c.x());
    }
    cut_left[i] = std::max(0.0, lo);
    cut_right[i] = std::min<double>(photo.width, hi);
  }
  for (size_t i = 0; i + 1 < walls.size(); ++i) {
    const double seam = 0.5 * (cut_right[i] + cut_left[i + 1]);
    if (cut_left[i + 1] < cut_left[i] || cut_right[i] > cut_right[i + 1])
      return R::failure(named(walls[i + 1], i + 1) + ": the walls must be listed left to right");
    cut_right[i] = std::min(cut_right[i], seam);
    cut_left[i + 1] = std::max(cut_left[i + 1], seam);
  }
  PiecewiseCamera pieces;
  pieces.source_size = photo;
  pieces.target_size = out;
  double offset = 0.0;
  for (size_t i = 0; i < walls.size(); ++i) {
    const Layout& l = layouts[i];
    // photo px → wall (u, v) → output px, exact: a homography; fitted as one from a grid of its
    // own points (the fitter conditions them and builds the tensors, eq 10).
    auto target = [&](const Eigen::Vector2d& p) {
      const Eigen::Vector3d r = ray(p);
      const Eigen::Vector3d X = r * (l.plane.d / l.plane.n.dot(r));
      const double u = l.eu.dot(X - l.origin), v = l.ev.dot(X - l.origin);
      return Eigen::Vector2d(offset + scale * (u - l.umin), scale * (tallest - (v - l.vmin)));
    };
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& c : walls[i].photo_px) box.extend(c);
    std::vector<PointMatch> matches;
    for (int a = 0; a <= 6; ++a)
      for (int b = 0; b <= 6; ++b) {
        const Eigen::Vector2d p(box.min().x() + box.sizes().x() * a / 6.0,
                                box.min().y() + box.sizes().y() * b / 6.0);
        if (!(l.plane.n.dot(ray(p)) < -1e-6)) continue;  // beyond the plane's horizon
        PointMatch m;
        m.source = p;
        m.target = target(p);
        matches.push_back(m);
      }
    FitOptions fit;
    fit.model = ModelClass::Homography;
    fit.refine = false;
    fit.restarts = 0;
    fit.diagnostics = false;
    fit.require_pole_free = false;
    FitSummary fitted = fitImageCamera(matches, photo, out, fit);
    if (!fitted.status) return R::failure(named(walls[i], i) + ": " + fitted.status.message);
    CameraPatch patch;
    patch.rect = {cut_left[i], std::max(0.0, box.min().y()), cut_right[i],
                  std::min<double>(photo.height, box.max().y())};
    if (!(patch.rect.x1 > patch.rect.x0 && patch.rect.y1 > patch.rect.y0))
      return R::failure(named(walls[i], i) + ": hidden by its neighbours' outlines");
    patch.support = convexHull(walls[i].photo_px);
    patch.camera = std::move(fitted.camera);
    patch.model = "homography";
    patch.matches = static_cast<int>(matches.size());
    // The share of the outline cut off at the seams (sampled on the depth pixels' grid).
    long long in = 0, cut = 0;
    for (int y = static_cast<int>(box.min().y()); y <= static_cast<int>(box.max().y()); ++y)
      for (int x = static_cast<int>(box.min().x()); x <= static_cast<int>(box.max().x()); ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        if (!inside(walls[i].photo_px, p)) continue;
        ++in;
        if (!patch.rect.contains(p)) ++cut;
      }
    local.walls[i].left_out_share = in ? static_cast<double>(cut) / in : 0.0;
    pieces.patches.push_back(std::move(patch));
    offset += scale * (l.umax - l.umin);
  }
  Artcam camera(pieces.patches.front().camera);
  camera.pieces = std::move(pieces);
  if (const Status s = validateArtcam(camera); !s)
    return R::failure("the unfolding camera: " + s.message);
  local.size = out;
  local.px_per_unit = scale;
  if (summary) *summary = std::move(local);
  return R::success(std::move(camera));
}

}  // namespace artcam
