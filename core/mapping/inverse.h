// SPDX-License-Identifier: Apache-2.0
// Inverse position maps for the gather warp: for every output pixel centre
// (x + 0.5, y + 0.5) of a row, the source point in source pixels, or "no preimage".
//
// Conventions: pixel frames (centres at i + 0.5, rational_map.h). "No preimage" (transparent,
// never NaN) covers: beyond the pole curve x Q_n xᵀ = 0 (a denominator whose sign differs
// from its sign at the source frame centre), folded (Jacobian determinant sign differs from the
// centre's), and, for the rational kernel, Newton failing or missing the pixel centre by more
// than the residual tolerance. A point that maps fine but lies outside the source image IS a
// preimage: the sampler makes it transparent, fading at the border like every other tap.
#pragma once

#include "core/mapping/rational_map.h"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>

namespace artcam {

class InverseMap {
 public:
  virtual ~InverseMap() = default;
  // Fills source[x] and valid[x] (1: has a preimage) for x in [0, width) of output row y.
  // Safe to call concurrently from several threads.
  virtual void row(int y, int width, Eigen::Vector2d* source, unsigned char* valid) const = 0;
};

// Exact inverse of a homography (eq 1 with Q_i = sym(l h_iᵀ)): invert the 3×3
// matrix once and walk each row by one vector add per pixel.
// `target_from_source_px`: column form, pixels on both sides.
std::unique_ptr<InverseMap> makeHomographyInverse(const Eigen::Matrix3d& target_from_source_px,
                                                  FrameSize source_px);

struct RationalInverseOptions {
  double residual_tolerance_px = 1e-3;
  int max_iterations = 30;
};

// The reference the pole and fold tests compare with: the forward map at the source frame
// centre (or the nearest point around it where the map is defined). Empty when the map is
// undefined all around the centre.
struct CentreReference {
  Eigen::Vector2d source;
  Eigen::Vector2d target;
  Eigen::Matrix2d jacobian;
  unsigned denominator_signs = 0;
  bool det_positive = true;
};
std::optional<CentreReference> centreReference(const RationalMap& forward, FrameSize source_px);

// Damped Newton on forward(s) = t with the analytic Jacobian (rational_map.h); a solution must
// lie on the source centre's side of every pole curve and in the centre's fold.
// Shared by the row inverse below and the fused kernel (coordinates.h), which calls it only
// for the pixels its seed check rejects.
class NewtonInverse {
 public:
  // Throws std::invalid_argument when the map is undefined all around the source centre.
  NewtonInverse(RationalMap forward, FrameSize source_px, double residual_tolerance_px);

  // From `start`; false when it fails, misses t by more than the residual tolerance, or lands
  // beyond a pole curve or across the fold. `jacobian`, if given, receives the forward
  // Jacobian at `out` (the last evaluation's: the same numbers a new one there would give).
  bool solve(const Eigen::Vector2d& t, const Eigen::Vector2d& start, Eigen::Vector2d& out,
             int max_iterations, Eigen::Matrix2d* jacobian = nullptr) const;
  // As solve, but the first Newton step from `start` is taken without iterating on when it is
  // at most `accept_step` source pixels on each axis and the start lies on the centre's side of
  // every pole curve and of the fold: the fused kernel's check (coordinates.h). When the step
  // is longer, the check's evaluation is Newton's first. `one_step` says which happened (false
  // also for a start that already meets the convergence test: it is returned as solve would).
  bool acceptOrSolve(const Eigen::Vector2d& t, const Eigen::Vector2d& start, Eigen::Vector2d& out,
                     int max_iterations, double accept_step, bool& one_step) const;
  // From the forward map linearised at the source centre (the start of last resort).
  bool solveFromCentre(const Eigen::Vector2d& t, Eigen::Vector2d& out, int max_iterations,
                       Eigen::Matrix2d* jacobian = nullptr) const;

  const RationalMap& forward() const { return forward_; }
  const CentreReference& centre() const { return centre_; }
  double residualTolerance() const { return residual_tolerance_px_; }

 private:
  // accept_step > 0: acceptOrSolve's early acceptance (one_step then not null).
  bool solveImpl(const Eigen::Vector2d& t, const Eigen::Vector2d& start, Eigen::Vector2d& out,
                 int max_iterations, Eigen::Matrix2d* jacobian, double accept_step,
                 bool* one_step) const;

  RationalMap forward_;
  CentreReference centre_;
  double residual_tolerance_px_;
  bool has_linear_ = false;
  Eigen::Matrix2d centre_inverse_jacobian_ = Eigen::Matrix2d::Identity();
  double escape_ = 0.0;
};

// The general kernel: the inverse of a rational map is not rational, so each pixel
// is solved by damped Newton on forward(s) = t with the analytic Jacobian (rational_map.h).
// Starts, in order: `seed` (an approximate inverse camera, output px → source px, evaluated
// incrementally along the row; may be null), the previous pixel's solution on the row, and the
// forward map linearised at the source frame centre.
std::unique_ptr<InverseMap> makeRationalInverse(RationalMap forward, std::optional<RationalMap> seed,
                                                FrameSize source_px,
                                                const RationalInverseOptions& options);


}  // namespace artcam
