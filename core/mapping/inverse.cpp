// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/inverse.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace artcam {
namespace {

class HomographyInverse final : public InverseMap {
 public:
  HomographyInverse(const Eigen::Matrix3d& target_from_source, FrameSize source_px) {
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(target_from_source);
    if (!lu.isInvertible()) throw std::invalid_argument("the camera's homography is singular");
    source_from_target_ = lu.inverse();
    const double scale = source_from_target_.cwiseAbs().maxCoeff();
    if (!(scale > 0.0) || !source_from_target_.allFinite())
      throw std::invalid_argument("the camera's homography has no finite inverse");
    source_from_target_ /= scale;  // a positive factor keeps every sign below
    // With s_h = M t_h, the forward denominator at s_h / s_h3 is 1 / s_h3 (H M = I up to a
    // positive scale): so the pole test compares the sign of s_h3 with the centre's.
    const Eigen::Vector3d centre(source_px.width / 2.0, source_px.height / 2.0, 1.0);
    centre_sign_positive_ = (target_from_source * centre).z() * scale > 0.0;
  }

  void row(int y, int width, Eigen::Vector2d* source, unsigned char* valid) const override {
    Eigen::Vector3d h = source_from_target_ * Eigen::Vector3d(0.5, y + 0.5, 1.0);
    const Eigen::Vector3d step = source_from_target_.col(0);
    for (int x = 0; x < width; ++x, h += step) {
      const double w = h.z();
      const bool ok = centre_sign_positive_ ? w > 0.0 : w < 0.0;
      if (ok) {
        const double inv = 1.0 / w;
        source[x] = Eigen::Vector2d(h.x() * inv, h.y() * inv);
        valid[x] = source[x].allFinite() ? 1 : 0;
      } else {
        valid[x] = 0;
      }
    }
  }

 private:
  Eigen::Matrix3d source_from_target_;
  bool centre_sign_positive_ = true;
};

// From a close start Newton converges in 2–4 steps; a start that needs more is a poor one
// (near a pole of the seed, across a fold), and the next start is cheaper than persisting.
constexpr int kQuickIterations = 8;

class RationalInverse final : public InverseMap {
 public:
  RationalInverse(RationalMap forward, std::optional<RationalMap> seed, FrameSize source_px,
                  const RationalInverseOptions& options)
      : newton_(std::move(forward), source_px, options.residual_tolerance_px),
        seed_(std::move(seed)),
        options_(options) {}

  void row(int y, int width, Eigen::Vector2d* source, unsigned char* valid) const override {
    std::optional<RowQuadratics> seed_row;
    if (seed_) seed_row.emplace(seed_->stage(0), y);
    int run = 0;  // consecutive solved pixels just before x
    Eigen::Vector2d previous, before_previous;
    for (int x = 0; x < width; ++x) {
      const Eigen::Vector2d t(x + 0.5, y + 0.5);
      Eigen::Vector2d s, seed_start;
      const bool have_seed = seed_row && seed_row->current(seed_start);
      if (seed_row) seed_row->advance();
      bool ok = false;
      // Within a run of solved pixels, extrapolating the last two solutions is within ~1e-3 px
      // of the answer (one or two Newton steps).
      if (run >= 2) ok = newton_.solve(t, 2.0 * previous - before_previous, s, kQuickIterations);
      if (!ok && have_seed) ok = newton_.solve(t, seed_start, s, kQuickIterations);
      if (!ok && run >= 1) ok = newton_.solve(t, previous, s, kQuickIterations);
      if (!ok) ok = newton_.solveFromCentre(t, s, options_.max_iterations);
      valid[x] = ok ? 1 : 0;
      if (ok) {
        source[x] = s;
        before_previous = previous;
        previous = s;
        ++run;
      } else {
        run = 0;
      }
    }
  }

 private:
  NewtonInverse newton_;
  std::optional<RationalMap> seed_;
  RationalInverseOptions options_;
};

}  // namespace

NewtonInverse::NewtonInverse(RationalMap forward, FrameSize source_px, double residual_tolerance_px)
    : forward_(std::move(forward)), residual_tolerance_px_(residual_tolerance_px) {
  const auto centre = centreReference(forward_, source_px);
  if (!centre) throw std::invalid_argument("the camera's position map is undefined at the source centre");
  centre_ = *centre;
  const Eigen::FullPivLU<Eigen::Matrix2d> lu(centre_.jacobian);
  has_linear_ = lu.isInvertible();
  if (has_linear_) centre_inverse_jacobian_ = lu.inverse();
  // Iterates that wander this far from the frame have left the sheet of the map we render.
  escape_ = 10.0 * std::hypot(source_px.width, source_px.height);
}

bool NewtonInverse::solveFromCentre(const Eigen::Vector2d& t, Eigen::Vector2d& out,
                                    int max_iterations, Eigen::Matrix2d* jacobian) const {
  if (!has_linear_) return false;
  return solve(t, centre_.source + centre_inverse_jacobian_ * (t - centre_.target), out,
               max_iterations, jacobian);
}

bool NewtonInverse::solve(const Eigen::Vector2d& t, const Eigen::Vector2d& start,
                          Eigen::Vector2d& out, int max_iterations, Eigen::Matrix2d* jacobian) const {
  return solveImpl(t, start, out, max_iterations, jacobian, 0.0, nullptr);
}

bool NewtonInverse::acceptOrSolve(const Eigen::Vector2d& t, const Eigen::Vector2d& start,
                                  Eigen::Vector2d& out, int max_iterations, double accept_step,
                                  bool& one_step) const {
  one_step = false;
  return solveImpl(t, start, out, max_iterations, nullptr, accept_step, &one_step);
}

bool NewtonInverse::solveImpl(const Eigen::Vector2d& t, const Eigen::Vector2d& start,
                              Eigen::Vector2d& out, int max_iterations, Eigen::Matrix2d* jacobian,
                              double accept_step, bool* one_step) const {
  if (!start.allFinite()) return false;
  Eigen::Vector2d s = start, f;
  Eigen::Matrix2d j;
  unsigned signs = 0;
  if (!forward_.evaluate(s, f, &j, &signs)) return false;
  Eigen::Vector2d r = f - t;
  double rn = r.norm();
  // Quadratic convergence takes a residual of 1e-3 px to far below this in one more step.
  const double converged = 1e-4 * residual_tolerance_px_;
  for (int it = 0; it < max_iterations && rn > converged; ++it) {
    const double det = j.determinant();
    if (!(std::abs(det) > 0.0)) return false;
    const Eigen::Vector2d step =
        -Eigen::Vector2d(j(1, 1) * r.x() - j(0, 1) * r.y(), -j(1, 0) * r.x() + j(0, 0) * r.y()) /
        det;
    if (!step.allFinite()) return false;
    // acceptOrSolve's check is the first step: taken as the check (coordinates.h) takes it when
    // it is short enough (a start already converged is taken by the tests below instead).
    if (it == 0 && accept_step > 0.0 && std::abs(step.x()) <= accept_step &&
        std::abs(step.y()) <= accept_step && signs == centre_.denominator_signs &&
        (det > 0.0) == centre_.det_positive) {
      out = s + step;
      *one_step = true;
      return true;
    }
    // Backtrack until the residual drops: keeps the iterate off the pole curve, where a full
    // step can jump to another branch of the rational map.
    double lambda = 1.0;
    bool improved = false;
    for (int k = 0; k < 12 && !improved; ++k, lambda *= 0.5) {
      const Eigen::Vector2d trial = s + lambda * step;
      Eigen::Vector2d tf;
      Eigen::Matrix2d tj;
      unsigned ts = 0;
      if (!forward_.evaluate(trial, tf, &tj, &ts)) continue;
      const double trn = (tf - t).norm();
      if (trn < rn) {
        s = trial;
        f = tf;
        j = tj;
        signs = ts;
        r = tf - t;
        rn = trn;
        improved = true;
      }
    }
    if (!improved) break;  // stalled: at rounding level or at a local minimum; judged below
    if ((s - centre_.source).norm() > escape_) return false;
  }
  if (!(rn <= residual_tolerance_px_)) return false;
  if (signs != centre_.denominator_signs) return false;               // beyond a pole curve
  if ((j.determinant() > 0.0) != centre_.det_positive) return false;  // folded over
  out = s;
  if (jacobian) *jacobian = j;
  return true;
}

std::optional<CentreReference> centreReference(const RationalMap& forward, FrameSize source_px) {
  const Eigen::Vector2d centre(source_px.width / 2.0, source_px.height / 2.0);
  const double step = 0.01 * std::max(source_px.width, source_px.height);
  // The centre itself, then a small spiral around it in case a pole passes exactly through it.
  for (int ring = 0; ring < 4; ++ring) {
    for (int k = 0; k < (ring == 0 ? 1 : 8); ++k) {
      const double a = k * std::numbers::pi / 4.0;
      const Eigen::Vector2d s = centre + ring * step * Eigen::Vector2d(std::cos(a), std::sin(a));
      CentreReference ref;
      if (!forward.evaluate(s, ref.target, &ref.jacobian, &ref.denominator_signs)) continue;
      const double det = ref.jacobian.determinant();
      if (!(std::abs(det) > 0.0)) continue;
      ref.source = s;
      ref.det_positive = det > 0.0;
      return ref;
    }
  }
  return std::nullopt;
}

std::unique_ptr<InverseMap> makeHomographyInverse(const Eigen::Matrix3d& target_from_source_px,
                                                  FrameSize source_px) {
  return std::make_unique<HomographyInverse>(target_from_source_px, source_px);
}

std::unique_ptr<InverseMap> makeRationalInverse(RationalMap forward, std::optional<RationalMap> seed,
                                                FrameSize source_px,
                                                const RationalInverseOptions& options) {
  return std::make_unique<RationalInverse>(std::move(forward), std::move(seed), source_px, options);
}

}  // namespace artcam
