// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/point_inverse.h"

#include <algorithm>

namespace artcam {
namespace {

// The warp's Newton settings (RationalInverseOptions): a preimage maps within 1e-3 px of its
// target, and converges far below that (inverse.cpp).
constexpr double kResidualTolerancePx = 1e-3;
constexpr int kMaxIterations = 30;

}  // namespace

PointInverse::PointInverse(const Camera& camera, FrameSize source_px, FrameSize target_px)
    : source_px_(source_px),
      target_px_(target_px),
      newton_(RationalMap(camera, source_px, target_px), source_px, kResidualTolerancePx) {
  central_ = CentralInverse::detect(newton_.forward(), source_px, newton_.centre());
}

std::optional<Eigen::Vector2d> PointInverse::sourceOf(
    const Eigen::Vector2d& target, const std::optional<Eigen::Vector2d>& start) const {
  if (!target.allFinite()) return std::nullopt;
  Eigen::Vector2d s;
  if (central_) {
    if (!central_->solve(target, s)) return std::nullopt;
    return s;
  }
  if (start && newton_.solve(target, *start, s, kMaxIterations)) return s;
  // The target read in the source frame: for a mild warp the nearest start there is.
  const Eigen::Vector2d as_source(target.x() * source_px_.width / std::max(1, target_px_.width),
                                  target.y() * source_px_.height / std::max(1, target_px_.height));
  if (newton_.solve(target, as_source, s, kMaxIterations)) return s;
  if (newton_.solveFromCentre(target, s, kMaxIterations)) return s;
  return std::nullopt;
}

std::optional<Eigen::Vector2d> PointInverse::targetOf(const Eigen::Vector2d& source) const {
  Eigen::Vector2d t;
  if (!newton_.forward().evaluate(source, t, nullptr)) return std::nullopt;
  return t;
}

}  // namespace artcam
