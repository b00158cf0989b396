// SPDX-License-Identifier: Apache-2.0
#include "core/piecewise/unfold_walls.h"

#include "core/fit/fit_image.h"
#include "core/model/piecewise_camera.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

namespace artcam {
namespace {

constexpr int kMinDepthSamples = 50;

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

// The homography taking four points to four (column form, (y, 1) ∝ H (x, 1)), by the DLT on
// points moved to their centroid and scaled to unit spread on both sides; empty when three of
// them are collinear.
std::optional<Eigen::Matrix3d> homographyFrom4(const std::array<Eigen::Vector2d, 4>& from,
                                               const std::array<Eigen::Vector2d, 4>& to) {
  auto conditioner = [](const std::array<Eigen::Vector2d, 4>& q) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : q) mean += p / 4.0;
    double spread = 0.0;
    for (const auto& p : q) spread += (p - mean).norm() / 4.0;
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    const double k = spread > 0 ? 1.0 / spread : 1.0;
    t(0, 0) = t(1, 1) = k;
    t(0, 2) = -k * mean.x();
    t(1, 2) = -k * mean.y();
    return t;
  };
  const Eigen::Matrix3d tf = conditioner(from), tt = conditioner(to);
  Eigen::Matrix<double, 8, 8> a;
  Eigen::Matrix<double, 8, 1> b;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d x = (tf * from[i].homogeneous()).hnormalized();
    const Eigen::Vector2d y = (tt * to[i].homogeneous()).hnormalized();
    a.row(2 * i) << x.x(), x.y(), 1, 0, 0, 0, -y.x() * x.x(), -y.x() * x.y();
    a.row(2 * i + 1) << 0, 0, 0, x.x(), x.y(), 1, -y.y() * x.x(), -y.y() * x.y();
    b(2 * i) = y.x();
    b(2 * i + 1) = y.y();
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 8, 8>> lu(a);
  if (lu.rank() < 8) return std::nullopt;
  const Eigen::Matrix<double, 8, 1> h = lu.solve(b);
  Eigen::Matrix3d m;
  m << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0;
  return tt.inverse() * m * tf;
}

std::string named(const WallOutline& w, size_t i) {
  return "wall " + (w.name.empty() ? std::to_string(i + 1) : "\"" + w.name + "\"");
}

}  // namespace

bool insideOutline(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool in = false;
  if (poly.empty()) return in;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

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
  // The depth at a photo point; 0 outside the photo or where the depth map has none.
  auto depthAt = [&](const Eigen::Vector2d& p) {
    if (!(p.x() >= 0 && p.y() >= 0 && p.x() < photo.width && p.y() < photo.height)) return 0.0f;
    const int dx = std::min(depth.width - 1, static_cast<int>(p.x() * sx));
    const int dy = std::min(depth.height - 1, static_cast<int>(p.y() * sy));
    const float z = *depth.pixel(dx, dy);
    return z > 0.0f && std::isfinite(z) ? z : 0.0f;
  };
  auto project = [&](const Eigen::Vector3d& X) {
    return Eigen::Vector2d(pp.x() + f * X.x() / X.z(), pp.y() + f * X.y() / X.z());
  };

  struct Layout {
    Plane plane;
    Eigen::Vector3d origin, eu, ev;
    double umin, umax, vmin, vmax;
    std::vector<Eigen::Vector2d> corner_uv;  // the outline's corners on the plane
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
        if (!insideOutline(inner, p)) continue;
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
      l.corner_uv.emplace_back(u, v);
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
  double scale = options.px_per_unit > 0 ? options.px_per_unit : photo.width / total_width;
  FrameSize out{std::max(1, static_cast<int>(std::ceil(scale * total_width))),
                std::max(1, static_cast<int>(std::ceil(scale * tallest)))};
  // In a given frame: the walls at the largest scale that fits, from its top-left corner (the
  // picture they make alone, then transparent to the frame's other sides; what reaches past the
  // picture's top and left, the roof's reach below, is cut at the frame's edge as it is there).
  if (options.frame.isImage()) {
    scale = std::min(options.frame.width / total_width, options.frame.height / tallest);
    out = options.frame;
  }
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
  // The roof over wall i (the paper's Fig 2 stretches it to fit the unfolded walls): the band of
  // the picture above a wall shorter than the tallest is filled with what the photo shows over
  // the wall's top edge, up to where the depth ends. On the wall's plane (u along the base, v
  // up), the roof's top is found column by column, walking up from the top edge until the
  // depth has stopped for a few pixels (the sky), and taken at the median over the columns: a
  // ridge parallel to the eaves lies on a line parallel to the top edge there (central
  // projection onto a plane the ridge is parallel to), and the median is that line wherever the
  // ridge spans most of the wall. The quadrilateral from the top edge to that line is mapped
  // onto the band by the homography that keeps the top edge where the wall put it and lifts its
  // other side to the picture's top, so wall and roof meet on the edge; the roof is seen as the
  // photo shows it, stretched, not orthogonally (its plane is not fitted). None for a wall whose
  // top is not one edge across its width (a gable), or with no depth over it.
  struct RoofBand {
    CameraPatch patch;
    double height = 0.0, stretch = 0.0;
  };
  auto roofBand = [&](size_t i) -> std::optional<RoofBand> {
    const Layout& l = layouts[i];
    const double top_v = l.vmin + tallest;  // the picture's top on this wall's plane
    const double pixel = 1.0 / scale;       // one output pixel, depth units
    if (top_v - l.vmax < 2.0 * pixel) return std::nullopt;
    const size_t n = l.corner_uv.size();
    size_t edge = n;
    double best = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < n; ++k) {
      const double low = std::min(l.corner_uv[k].y(), l.corner_uv[(k + 1) % n].y());
      if (low > best) best = low, edge = k;
    }
    Eigen::Vector2d a = l.corner_uv[edge], b = l.corner_uv[(edge + 1) % n];
    if (a.x() > b.x()) std::swap(a, b);
    const double width = l.umax - l.umin, height = l.vmax - l.vmin;
    if (best < l.vmax - 0.02 * height || b.x() - a.x() < 0.9 * width) return std::nullopt;
    auto onPlane = [&](double u, double v) { return l.origin + u * l.eu + v * l.ev; };
    const double step = 0.5 * pixel;
    const int columns = 64, gap_steps = 12;
    const int max_steps = static_cast<int>(std::ceil(4.0 * (top_v - l.vmin) / step));
    std::vector<double> tops;
    for (int c = 0; c < columns; ++c) {
      const double t = 0.02 + 0.96 * (c + 0.5) / columns;
      const double u = a.x() + t * (b.x() - a.x());
      const double v0 = a.y() + t * (b.y() - a.y());
      double last = v0;
      int misses = 0;
      for (int k = 1; k <= max_steps && misses < gap_steps; ++k) {
        const Eigen::Vector3d X = onPlane(u, v0 + k * step);
        if (!(X.z() > 0)) break;
        const Eigen::Vector2d p = project(X);
        if (!(p.x() >= 0 && p.y() >= 0 && p.x() < photo.width && p.y() < photo.height)) break;
        if (depthAt(p) > 0.0f) {
          last = v0 + k * step;
          misses = 0;
        } else {
          ++misses;
        }
      }
      tops.push_back(last - v0);
    }
    std::nth_element(tops.begin(), tops.begin() + tops.size() / 2, tops.end());
    const double roof = tops[tops.size() / 2];
    if (roof < 2.0 * pixel) return std::nullopt;
    const double band = top_v - std::max(a.y(), b.y());
    const std::array<Eigen::Vector2d, 4> from{a, b, {b.x(), b.y() + roof}, {a.x(), a.y() + roof}};
    const std::array<Eigen::Vector2d, 4> to{a, b, {b.x(), top_v}, {a.x(), top_v}};
    const auto g = homographyFrom4(from, to);
    if (!g) return std::nullopt;
    // The support reaches past the band's top and ends by a mesh cell (64 photo pixels: the
    // renderer keeps a cell only where its centre is supported, piecewise_render.h); what lies
    // past them maps outside the band, above the picture or beyond the seams, and is cut there.
    const Eigen::Vector3d pa = onPlane(a.x(), a.y()), pb = onPlane(b.x(), b.y());
    if (!(pa.z() > 0 && pb.z() > 0)) return std::nullopt;
    const double photo_px_per_unit = (project(pa) - project(pb)).norm() / (b - a).norm();
    const double reach_units = 64.0 / std::max(photo_px_per_unit, 1e-9);
    const Eigen::Vector2d edge_dir = (b - a).normalized();
    const double grow = reach_units;
    const std::array<Eigen::Vector2d, 4> reach{a - grow * edge_dir,
                                               b + grow * edge_dir,
                                               {b.x() + grow * edge_dir.x(), b.y() + roof + grow},
                                               {a.x() - grow * edge_dir.x(), a.y() + roof + grow}};
    std::vector<Eigen::Vector2d> quad;
    for (const Eigen::Vector2d& q : reach) {
      const Eigen::Vector3d X = onPlane(q.x(), q.y());
      if (!(X.z() > 0)) return std::nullopt;
      quad.push_back(project(X));
    }
    auto target = [&](const Eigen::Vector2d& p) -> std::optional<Eigen::Vector2d> {
      const Eigen::Vector3d r = ray(p);
      const double along = l.plane.n.dot(r);
      if (!(along < -1e-6)) return std::nullopt;
      const Eigen::Vector3d X = r * (l.plane.d / along);
      const Eigen::Vector3d uvw =
          *g * Eigen::Vector3d(l.eu.dot(X - l.origin), l.ev.dot(X - l.origin), 1.0);
      if (!(std::abs(uvw.z()) > 1e-12)) return std::nullopt;
      const Eigen::Vector2d uv = uvw.hnormalized();
      return Eigen::Vector2d(offset + scale * (uv.x() - l.umin),
                             scale * (tallest - (uv.y() - l.vmin)));
    };
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& q : quad) box.extend(q);
    std::vector<PointMatch> matches;
    for (int ka = 0; ka <= 6; ++ka)
      for (int kb = 0; kb <= 6; ++kb) {
        const Eigen::Vector2d p(box.min().x() + box.sizes().x() * ka / 6.0,
                                box.min().y() + box.sizes().y() * kb / 6.0);
        if (const auto t = target(p)) {
          PointMatch m;
          m.source = p;
          m.target = *t;
          matches.push_back(m);
        }
      }
    FitOptions fit;
    fit.model = ModelClass::Homography;
    fit.refine = false;
    fit.restarts = 0;
    fit.diagnostics = false;
    fit.require_pole_free = false;
    FitSummary fitted = fitImageCamera(matches, photo, out, fit);
    if (!fitted.status) return std::nullopt;
    RoofBand result;
    result.patch.rect = {cut_left[i], std::max(0.0, box.min().y()), cut_right[i],
                         std::min<double>(photo.height, box.max().y())};
    if (!(result.patch.rect.x1 > result.patch.rect.x0 &&
          result.patch.rect.y1 > result.patch.rect.y0))
      return std::nullopt;
    result.patch.support = convexHull(quad);
    result.patch.camera = std::move(fitted.camera);
    result.patch.model = "homography";
    result.patch.matches = static_cast<int>(matches.size());
    result.height = roof;
    result.stretch = band / roof;
    return result;
  };
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
        if (!insideOutline(walls[i].photo_px, p)) continue;
        ++in;
        if (!patch.rect.contains(p)) ++cut;
      }
    local.walls[i].left_out_share = in ? static_cast<double>(cut) / in : 0.0;
    pieces.patches.push_back(std::move(patch));
    if (options.stretch_roof) {
      if (auto roof = roofBand(i)) {
        pieces.patches.push_back(std::move(roof->patch));
        local.walls[i].roof_height = roof->height;
        local.walls[i].roof_stretch = roof->stretch;
      }
    }
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
