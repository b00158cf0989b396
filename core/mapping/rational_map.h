// SPDX-License-Identifier: Apache-2.0
// The 2D position map of a camera in PIXEL frames, for renderers.
//
// Conventions: pixel centres at i + 0.5 (frames.h). A camera stores its tensors in normalised
// frames; here the first stage's input is re-expressed in source pixels and the last stage's
// output in target pixels, so one stage computes, for x = (u, v, 1) a row vector,
//   n_i = x Q_i xᵀ (eq 3, the position block only), y_i = n_i / n_3 (eq 1, 2).
// A chain composes its stages (one after the other); middle stages stay in normalised coordinates.
//
// Only the position block is read (its pp sub-blocks): callers check beforehand that the
// geometry does not depend on colour or depth (CameraStructure::geometry_depends_on_attributes).
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <vector>

namespace artcam {

class RationalMap {
 public:
  RationalMap() = default;
  // `source_px`/`target_px`: the pixel sizes the map should work in (any resolution of the
  // camera's frames). Throws std::invalid_argument without a 2D position block.
  RationalMap(const Camera& camera, FrameSize source_px, FrameSize target_px);

  // Forward map with the analytic Jacobian d target / d source (may be null). Returns false
  // where a denominator vanishes or the result is not finite; outputs are then untouched.
  // `denominator_signs` (may be null) receives one bit per stage: bit s set when stage s's
  // denominator n_3 is negative, for the pole test.
  bool evaluate(const Eigen::Vector2d& source, Eigen::Vector2d& target, Eigen::Matrix2d* jacobian,
                unsigned* denominator_signs = nullptr) const;

  // The forward Jacobian's derivative along `direction` (source pixels) at `source`:
  // d/dλ J(source + λ direction) at λ = 0, from the forms' second derivatives (eq 2
  // differentiated once more). False for a chain (the caller then differences) or where the
  // map is undefined.
  bool jacobianDerivative(const Eigen::Vector2d& source, const Eigen::Vector2d& direction,
                          Eigen::Matrix2d& out) const;

  // A one-stage map at kBatch points at once (false for a chain, which the caller then
  // evaluates point by point): the target, the Jacobian's entries and the denominator n_3, in
  // plain loops that vectorise (AVX2 by runtime dispatch). No check: a point on the pole gives
  // infinities or NaN, which the caller's comparisons reject.
  static constexpr int kBatch = 12;
  struct Batch {
    double x[kBatch], y[kBatch], j00[kBatch], j01[kBatch], j10[kBatch], j11[kBatch], den[kBatch];
  };
  bool evaluateBatch(const double* u, const double* v, Batch& out) const;

  int stageCount() const { return static_cast<int>(stages_.size()); }
  // Stage s's three symmetric 3×3 forms (u, v, homogeneous).
  const std::vector<Eigen::Matrix3d>& stage(int s) const { return stages_[s]; }

  // One stage's form x Q xᵀ, x = (u, v, 1), as n = a u² + b uv + c u + d v² + e v + f: a
  // one-stage map (every camera but a composed chain) is evaluated from these, in fewer
  // operations than the matrix products; Newton, the node solves and the checks all come
  // through here.
  struct Form {
    double a = 0, b = 0, c = 0, d = 0, e = 0, f = 0;
  };

 private:
  bool evaluateSingle(const Eigen::Vector2d& source, Eigen::Vector2d& target, Eigen::Matrix2d* jacobian,
                      unsigned* denominator_signs) const;
  static void batchDispatched(const Form* forms, const double* u, const double* v, Batch& out);

  std::vector<std::vector<Eigen::Matrix3d>> stages_;
  Form single_[3];
};

// Evaluates one rational stage along a row of pixel centres (x + 0.5, y + 0.5) by forward
// differences: each quadratic form n(x) = a x² + b x + c advances with two adds per pixel.
// The rounding error grows like (row length)² · ε, about 1e-8 relative on a
// 6000-pixel row: fine for seeds that Newton refines, not for final positions.
class RowQuadratics {
 public:
  // Starts at output pixel x0 of row y: the fused kernel re-anchors every span this way, so the
  // drift stays that of one span (span² · ε) instead of a whole row's.
  RowQuadratics(const std::vector<Eigen::Matrix3d>& q, int y, int x0 = 0);
  double numerator(int i) const { return value_[i]; }
  double delta(int i) const { return delta_[i]; }
  double second(int i) const { return second_[i]; }
  // The stage's output at the current pixel; false (and no write) where n_3 = 0 or non-finite.
  bool current(Eigen::Vector2d& out) const;
  void advance();

 private:
  double value_[3];
  double delta_[3];
  double second_[3];
};

}  // namespace artcam
