// SPDX-License-Identifier: Apache-2.0
#include "core/fit/poles.h"

#include "core/model/frames.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace artcam {
namespace {

double denominatorAt(const Eigen::Matrix3d& q, const Eigen::Vector2d& p) {
  const Eigen::Vector3d x(p.x(), p.y(), 1.0);
  return x.dot(q * x);
}

}  // namespace

std::string PoleCheck::describe() const {
  char buf[160];
  if (!checked) return "pole check applies to single-stage 2D position cameras only";
  if (pole_free && !std::isfinite(margin))
    return "the denominator is zero or not finite over the source frame";
  if (pole_free)
    std::snprintf(buf, sizeof buf, "pole-free over the source frame (margin %.3g)", margin);
  else
    std::snprintf(buf, sizeof buf,
                  "has a pole in the source frame (its denominator vanishes near pixel %.1f, %.1f)",
                  worst_pixel.x(), worst_pixel.y());
  return buf;
}

PoleCheck checkDenominator(const Eigen::Matrix3d& q, const Eigen::Vector2d& lo,
                           const Eigen::Vector2d& hi) {
  // D(u, v) = a u² + 2b uv + c v² + 2d u + 2e v + f with a = q00, b = q01, … (q symmetric part).
  const Eigen::Matrix3d s = 0.5 * (q + q.transpose());
  std::vector<Eigen::Vector2d> candidates = {
      {lo.x(), lo.y()}, {hi.x(), lo.y()}, {lo.x(), hi.y()}, {hi.x(), hi.y()}};
  // Edge vertices: along u at fixed v, dD/du = 2(a u + b v + d) = 0; along v likewise.
  for (const double v : {lo.y(), hi.y()})
    if (s(0, 0) != 0.0) {
      const double u = -(s(0, 1) * v + s(0, 2)) / s(0, 0);
      if (u > lo.x() && u < hi.x()) candidates.emplace_back(u, v);
    }
  for (const double u : {lo.x(), hi.x()})
    if (s(1, 1) != 0.0) {
      const double v = -(s(0, 1) * u + s(1, 2)) / s(1, 1);
      if (v > lo.y() && v < hi.y()) candidates.emplace_back(u, v);
    }
  const Eigen::Matrix2d hessian = s.topLeftCorner<2, 2>();
  if (std::abs(hessian.determinant()) > 1e-300) {
    const Eigen::Vector2d c = hessian.lu().solve(-s.topRightCorner<2, 1>());
    if (c.x() > lo.x() && c.x() < hi.x() && c.y() > lo.y() && c.y() < hi.y())
      candidates.push_back(c);
  }
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest, smallest_abs = lowest, largest_abs = 0.0;
  PoleCheck out;
  for (const Eigen::Vector2d& p : candidates) {
    const double d = denominatorAt(s, p);
    lowest = std::min(lowest, d);
    highest = std::max(highest, d);
    largest_abs = std::max(largest_abs, std::abs(d));
    if (std::abs(d) < smallest_abs) {
      smallest_abs = std::abs(d);
      out.worst_pixel = p;
    }
  }
  // A sign change means a zero crossing in between (the rectangle is connected).
  out.pole_free = (lowest > 0.0) || (highest < 0.0);
  out.margin = out.pole_free && largest_abs > 0.0 ? smallest_abs / largest_abs : 0.0;
  if (!out.pole_free) {
    // Locate a zero for the message: bisect between the lowest and highest candidates.
    Eigen::Vector2d a = candidates.front(), b = candidates.front();
    for (const Eigen::Vector2d& p : candidates) {
      if (denominatorAt(s, p) == lowest) a = p;
      if (denominatorAt(s, p) == highest) b = p;
    }
    for (int i = 0; i < 60; ++i) {
      const Eigen::Vector2d mid = 0.5 * (a + b);
      (denominatorAt(s, mid) < 0.0 ? a : b) = mid;
    }
    out.worst_pixel = 0.5 * (a + b);
  }
  return out;
}

PoleCheck checkPoles(const Camera& camera) {
  const BlockLayout& layout = camera.layout();
  PoleCheck out;
  if (layout.blocks.size() != 1 || layout.blocks[0].size != 3 || camera.stages().size() != 1) {
    out.checked = false;  // object space has no frame; chains and attributes: not yet
    return out;
  }
  const FrameSize f = camera.sourceSize();
  const Eigen::Vector2d lo = normalizedFromPixel(f, {0.0, 0.0});
  const Eigen::Vector2d hi = normalizedFromPixel(f, {static_cast<double>(f.width), static_cast<double>(f.height)});
  out = checkDenominator(Eigen::Matrix3d(camera.stages()[0].q[2]), lo, hi);
  out.worst_pixel = pixelFromNormalized(f, out.worst_pixel);
  return out;
}

}  // namespace artcam
