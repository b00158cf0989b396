// SPDX-License-Identifier: Apache-2.0
#include "core/fit/fit_image.h"

#include "core/fit/cross_validation.h"
#include "core/fit/dlt.h"
#include "core/fit/normalize.h"
#include "core/fit/poles.h"
#include "core/fit/refine.h"
#include "core/fit/report_format.h"
#include "core/fit/robust.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <sstream>

namespace artcam {

namespace {

// Held-out errors below this are "exact" (target units): differences there are rounding.
constexpr double kExactError = 1e-6;

// One fitting problem, whatever its dimension: points in the frames the tensors are stored in
// (normalised for images, raw for object space), and how to turn tensors into a camera.
struct Problem {
  int dimension = 2;
  Points src, dst;
  double target_units_per_stored_unit = 1.0;  // pixels per normalised unit for images
  std::function<Camera(const std::vector<Eigen::MatrixXd>&)> make_camera;
  std::vector<ModelClass> ladder;
  // Images: the source frame in normalised coordinates, for the pole check.
  Eigen::Vector2d frame_lo = Eigen::Vector2d(-1, -1);
  Eigen::Vector2d frame_hi = Eigen::Vector2d(1, 1);

  int size() const { return static_cast<int>(src.cols()); }
  Problem subset(const std::vector<int>& keep) const {
    Problem p;
    p.dimension = dimension;
    p.src = src(Eigen::all, keep);
    p.dst = dst(Eigen::all, keep);
    p.target_units_per_stored_unit = target_units_per_stored_unit;
    p.make_camera = make_camera;
    p.ladder = ladder;
    p.frame_lo = frame_lo;
    p.frame_hi = frame_hi;
    return p;
  }
};

struct ModelFit {
  Status status;
  Camera camera;
  Eigen::VectorXd singular_values;
  std::string note;
  double algebraic_rms = -1.0;  // stored units, before refinement
  PoleCheck poles;
};

std::string moreMatches(int have, int need) {
  const int more = need - have;
  return std::to_string(more) + " more well-spread match" + (more == 1 ? "" : "es") +
         " would determine it";
}

// Scale so the largest entry is 1 and the denominator is positive at the frame centre: the
// same camera, written the same way whichever null-vector sign the SVD returned.
void canonicalise(std::vector<Eigen::MatrixXd>& q) {
  double scale = 0.0;
  for (const Eigen::MatrixXd& m : q) scale = std::max(scale, m.cwiseAbs().maxCoeff());
  const Eigen::Index h = q.back().rows() - 1;
  if (q.back()(h, h) < 0.0) scale = -scale;
  if (scale != 0.0)
    for (Eigen::MatrixXd& m : q) m /= scale;
}

std::optional<Eigen::VectorXd> mapStored(const Camera& camera, const Eigen::VectorXd& p) {
  Eigen::VectorXd x(p.size() + 1);
  x << p, 1.0;
  const Eigen::VectorXd z = camera.evaluateHomogeneous(x);
  const double w = z[p.size()];
  if (w == 0.0) return std::nullopt;
  Eigen::VectorXd y = z.head(p.size()) / w;
  if (!y.allFinite()) return std::nullopt;
  return y;
}

ModelFit fitAlgebraic(ModelClass model, const Problem& pb, bool condition) {
  ModelFit out;
  const int m = pb.size();
  const int need = minimumMatches(model, pb.dimension);
  const std::string name(modelClassName(model));
  if (m < need) {
    out.status = Status::failure(std::to_string(m) + " match" + (m == 1 ? "" : "es") + "; the " +
                                 name + " model needs at least " + std::to_string(need) + " (" +
                                 moreMatches(m, need) + ")");
    return out;
  }
  const int distinct = countDistinct(pb.src, need);
  if (distinct < need) {
    out.status = Status::failure("only " + std::to_string(distinct) +
                                 " distinct source points among " + std::to_string(m) +
                                 " matches; the " + name + " model needs " + std::to_string(need) +
                                 " (" + moreMatches(distinct, need) + ")");
    return out;
  }
  const bool needs_spread = model != ModelClass::Translation && model != ModelClass::Similarity;
  if (needs_spread && spreadRatio(pb.src) < 1e-7) {
    out.status = Status::failure("all " + std::to_string(m) + " source points lie on one " +
                                 (pb.dimension == 2 ? "line" : "plane") + "; the " + name +
                                 " model needs points spread over the " +
                                 (pb.dimension == 2 ? "image" : "volume"));
    return out;
  }

  const Eigen::Index n = pb.dimension + 1;
  const bool use_conditioning = condition && model != ModelClass::Translation;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd ts = use_conditioning ? conditioningTransform(pb.src) : identity;
  const Eigen::MatrixXd td = use_conditioning ? conditioningTransform(pb.dst) : identity;
  // Many 2D matches: one pass of moments (conditioned on the fly) serves both the conic test
  // and the solve; the other solvers take conditioned copies of the points.
  std::optional<QuadraticMoments2d> moments;
  if (model == ModelClass::Quadratic && pb.dimension == 2 &&
      static_cast<size_t>(m) > kNormalEquationsFrom)
    moments = quadraticMoments2d(pb.src, pb.dst, Eigen::Matrix3d(ts), Eigen::Matrix3d(td));
  Points src = moments ? Points() : applyTransform(ts, pb.src);
  Points dst = moments ? Points() : applyTransform(td, pb.dst);
  const auto conicDegeneracy = [&] {
    return moments ? quadricDegeneracyFromMoments(moments->monomials) : quadricDegeneracy(src);
  };
  if (model == ModelClass::Quadratic && conicDegeneracy() < 1e-7) {
    out.status = Status::failure(
        "all " + std::to_string(m) + " source points lie on one " +
        (pb.dimension == 2 ? "conic (such as a circle or two lines)" : "quadric surface") +
        ", so the quadratic model is not determined; add matches off that " +
        (pb.dimension == 2 ? "curve" : "surface"));
    return out;
  }

  DltSolution s;
  switch (model) {
    case ModelClass::Translation: s = solveTranslation(src, dst); break;
    case ModelClass::Similarity: s = solveSimilarity(src, dst); break;
    case ModelClass::Affine: s = solveAffine(src, dst); break;
    case ModelClass::Homography: s = solveProjectiveDlt(src, dst); break;
    case ModelClass::Quadratic:
    case ModelClass::Auto:
      s = moments ? solveQuadraticMoments2d(*moments) : solveQuadraticDlt(src, dst);
      break;
  }
  out.singular_values = s.singular_values;
  if (s.null_dimension > 1 && model == ModelClass::Quadratic) {
    // Exact homography data: Q_i = sym(l h_iᵀ) fits for every line l, and an
    // arbitrary null vector is 0/0 along l. Fix l to the line at infinity: the homography.
    if (moments) {
      src = applyTransform(ts, pb.src);
      dst = applyTransform(td, pb.dst);
    }
    const DltSolution h = solveProjectiveDlt(src, dst);
    if (h.null_dimension == 1) {
      out.note = "the data are a homography (the quadratic null space is " +
                 std::to_string(s.null_dimension) +
                 "-dimensional), so l is fixed at the line at infinity";
      s = h;
    }
  }
  if (s.null_dimension > 1) {
    out.status = Status::failure("the matches do not determine the " + name +
                                 " model (its design matrix has a " +
                                 std::to_string(s.null_dimension) +
                                 "-dimensional null space); add well-spread matches");
    return out;
  }

  // Undo conditioning. Input: x_c(row) = x(row) tsᵀ, so Q ← tsᵀ Q ts (the row-vector form of the
  // paper's §5 substitution). Output: y = td⁻¹ y_c mixes the tensors, Q'_i = Σ_j (td⁻¹)_ij Q_j.
  const Eigen::MatrixXd td_inv = td.inverse();
  std::vector<Eigen::MatrixXd> q;
  if (s.linear) {
    q = liftHomography(td_inv * s.h * ts);
  } else {
    std::vector<Eigen::MatrixXd> qs;
    for (const Eigen::MatrixXd& qc : s.q) qs.push_back(ts.transpose() * qc * ts);
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::MatrixXd mixed = Eigen::MatrixXd::Zero(n, n);
      for (Eigen::Index j = 0; j < n; ++j) mixed += td_inv(i, j) * qs[j];
      q.push_back(std::move(mixed));
    }
  }
  canonicalise(q);
  for (const Eigen::MatrixXd& qi : q)
    if (!qi.allFinite()) {
      out.status = Status::failure("the " + name + " fit produced non-finite entries");
      return out;
    }
  out.camera = pb.make_camera(q);
  return out;
}


double rmsStored(const Camera& camera, const Problem& pb);

void restartNearby(ModelFit& best, double& best_rms, const Problem& pb, int restarts);

// Refines a quadratic start by LM (never worse, never trading pole-free for a pole), then
// restarts nearby in case LM stopped in a local minimum.
void refineFit(ModelFit& fit, const Problem& pb, int restarts) {
  RefineOptions ro;
  ro.frame_lo = pb.frame_lo;
  ro.frame_hi = pb.frame_hi;
  RefineSummary rs;
  fit.camera = refineReprojection(fit.camera, pb.src, pb.dst, ro, &rs);
  fit.algebraic_rms = rs.initial_rms;
  double rms = rs.final_rms;
  if (restarts > 0) restartNearby(fit, rms, pb, restarts);
}

// LM from the algebraic solution can stop in a local minimum: on the mustache lens at 3.97 px
// RMS where LM from starts a few percent away reaches 3.73 px, the multi-start best
// (tests/core/fit/test_lens_multistart.cpp). So the refined camera is perturbed a few times
// (seeded: the same matches give the same camera) and each perturbation refined on a subsample
// of at most 256 matches, which is cheap; the best of those that beats the refined camera on
// the subsample by more than 0.1 % is refined on all matches and kept if it is better there,
// and pole-free.
void restartNearby(ModelFit& best, double& best_rms, const Problem& pb, int restarts) {
  constexpr double kScale = 0.05;  // of the largest tensor entry
  constexpr int kSubsample = 256;
  std::vector<int> keep;
  const int m = pb.size();
  for (int k = 0; k < std::min(m, kSubsample); ++k)
    keep.push_back(static_cast<int>(static_cast<long long>(k) * m / std::min(m, kSubsample)));
  const Problem sub = pb.subset(keep);
  RefineOptions ro;
  ro.frame_lo = pb.frame_lo;
  ro.frame_hi = pb.frame_hi;

  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> jitter(-kScale, kScale);
  const Camera centre = best.camera;
  // The restarts may not come closer to a pole than the refined camera or RefineOptions'
  // floor allow (refine.h, min_pole_margin).
  const double margin_floor = std::min(
      ro.min_pole_margin,
      checkDenominator(Eigen::Matrix3d(centre.stages()[0].q[2]), pb.frame_lo, pb.frame_hi).margin);
  double largest = 0.0;
  for (const Eigen::MatrixXd& q : centre.stages()[0].q) largest = std::max(largest, q.cwiseAbs().maxCoeff());
  double best_sub = rmsStored(centre, sub) * (1.0 - 1e-3);
  std::optional<Camera> candidate;
  for (int t = 0; t < restarts; ++t) {
    Camera start = centre;
    for (Eigen::MatrixXd& q : start.stages()[0].q) {
      Eigen::Matrix3d noise;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) noise(r, c) = jitter(rng) * largest;
      q += 0.5 * (noise + noise.transpose());
    }
    if (!checkDenominator(Eigen::Matrix3d(start.stages()[0].q[2]), pb.frame_lo, pb.frame_hi).pole_free)
      continue;
    RefineSummary rs;
    Camera refined = refineReprojection(start, sub.src, sub.dst, ro, &rs);
    const PoleCheck sub_poles =
        checkDenominator(Eigen::Matrix3d(refined.stages()[0].q[2]), pb.frame_lo, pb.frame_hi);
    if (rs.final_rms < best_sub && sub_poles.pole_free && sub_poles.margin >= margin_floor) {
      best_sub = rs.final_rms;
      candidate = std::move(refined);
    }
  }
  if (!candidate) return;
  const Camera refined = sub.size() == m ? *candidate : refineReprojection(*candidate, pb.src, pb.dst, ro);
  const PoleCheck poles =
      checkDenominator(Eigen::Matrix3d(refined.stages()[0].q[2]), pb.frame_lo, pb.frame_hi);
  const double r = rmsStored(refined, pb);
  if (poles.pole_free && poles.margin >= margin_floor && r < best_rms) {
    best_rms = r;
    best.camera = refined;
    best.poles = poles;
  }
}

// The algebraic fit, then (images) refinement and the pole rule (poles.h).
ModelFit fitModel(ModelClass model, const Problem& pb, const FitOptions& options) {
  ModelFit fit = fitAlgebraic(model, pb, options.condition);
  if (!fit.status || pb.dimension != 2) return fit;
  const bool quadratic = model == ModelClass::Quadratic && fit.note.empty();
  if (quadratic && options.refine) refineFit(fit, pb, options.restarts);
  fit.poles = checkDenominator(Eigen::Matrix3d(fit.camera.stages()[0].q[2]), pb.frame_lo, pb.frame_hi);
  if (fit.poles.pole_free || !options.require_pole_free) return fit;

  const std::string where = fit.poles.describe();
  if (model != ModelClass::Quadratic) {
    fit.status = Status::failure("the " + std::string(modelClassName(model)) + " fitted to these "
                                 "matches " + where + " (normalised coordinates)");
    return fit;
  }
  // The algebraic solution put its zero curve through the frame (as with "mustache" lens
  // data); refinement started there would keep it. Start again from the lifted homography and
  // affine fits and keep the best pole-free result.
  ModelFit best;
  best.status = Status::failure("no pole-free quadratic camera was found for these matches: the "
                                "algebraic solution " + where + ", and refinement from the "
                                "homography and affine fits did not remove it");
  double best_rms = std::numeric_limits<double>::infinity();
  for (ModelClass start : {ModelClass::Homography, ModelClass::Affine}) {
    ModelFit f = fitAlgebraic(start, pb, options.condition);
    if (!f.status) continue;
    if (!checkDenominator(Eigen::Matrix3d(f.camera.stages()[0].q[2]), pb.frame_lo, pb.frame_hi).pole_free)
      continue;
    if (options.refine) refineFit(f, pb, options.restarts);
    f.poles = checkDenominator(Eigen::Matrix3d(f.camera.stages()[0].q[2]), pb.frame_lo, pb.frame_hi);
    const double r = rmsStored(f.camera, pb);
    if (f.poles.pole_free && r < best_rms) {
      best_rms = r;
      f.note = "the algebraic quadratic had a pole in the frame; refined from the " +
               std::string(modelClassName(start)) + " fit instead";
      f.singular_values = fit.singular_values;
      best = std::move(f);
    }
  }
  return best;
}

std::vector<double> residuals(const Camera& camera, const Problem& pb) {
  std::vector<double> out;
  out.reserve(pb.size());
  if (pb.dimension == 2 && camera.stages().size() == 1 && camera.dimension() == 3) {
    // Fixed-size evaluation: this runs over every match of every candidate and fold.
    const Eigen::Matrix3d q0 = camera.stages()[0].q[0], q1 = camera.stages()[0].q[1],
                          q2 = camera.stages()[0].q[2];
    for (int k = 0; k < pb.size(); ++k) {
      const Eigen::Vector3d x(pb.src(0, k), pb.src(1, k), 1.0);
      const double w = x.dot(q2 * x);
      const Eigen::Vector2d y(x.dot(q0 * x) / w, x.dot(q1 * x) / w);
      const double e = (y - Eigen::Vector2d(pb.dst(0, k), pb.dst(1, k))).norm();
      out.push_back(std::isfinite(e) ? e * pb.target_units_per_stored_unit
                                     : std::numeric_limits<double>::infinity());
    }
    return out;
  }
  for (int k = 0; k < pb.size(); ++k) {
    const auto y = mapStored(camera, pb.src.col(k));
    out.push_back(y ? (*y - pb.dst.col(k)).norm() * pb.target_units_per_stored_unit
                    : std::numeric_limits<double>::infinity());
  }
  return out;
}

double rms(const std::vector<double>& r) {
  if (r.empty()) return 0.0;
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return std::sqrt(sum / static_cast<double>(r.size()));
}

double rmsStored(const Camera& camera, const Problem& pb) {
  return rms(residuals(camera, pb)) / pb.target_units_per_stored_unit;
}

// Folds of the held-out error: leave-one-out up to 10 matches, 10 folds up to 5000, then 3
// (each fold's fit then still sees two thirds of a large set, at a third of the cost).
int foldCount(int matches) { return matches > 5000 ? 3 : std::min(matches, 10); }

// K-fold held-out RMS error in target units (cross_validation.h); NaN when the folds leave too
// few matches or a fold's fit fails.
double heldOutError(ModelClass model, const Problem& pb, const FitOptions& options) {
  const int m = pb.size();
  FitOptions fold_options = options;
  fold_options.restarts = 0;
  const auto sum =
      crossValidatedSum(m, foldCount(m), minimumMatches(model, pb.dimension),
                        [&](const std::vector<int>& train,
                            const std::vector<int>& held) -> std::optional<std::vector<double>> {
                          const ModelFit fit = fitModel(model, pb.subset(train), fold_options);
                          if (!fit.status) return std::nullopt;
                          std::vector<double> e = residuals(fit.camera, pb.subset(held));
                          for (double& v : e) v *= v;
                          return e;
                        });
  return sum ? std::sqrt(*sum / m) : std::numeric_limits<double>::quiet_NaN();
}

// Free parameters of a model class (the tensors up to scale): 2D translation 2, similarity 4,
// affine 6, homography 8, quadratic 17 (three 3×3 symmetric tensors, 18 entries, less scale).
int parameterCount(ModelClass model, int dimension) {
  const int n = dimension + 1;
  switch (model) {
    case ModelClass::Translation: return dimension;
    case ModelClass::Similarity: return 4;
    case ModelClass::Affine: return dimension * n;
    case ModelClass::Homography: return n * n - 1;
    case ModelClass::Quadratic:
    case ModelClass::Auto: return n * n * (n + 1) / 2 - 1;
  }
  return 0;
}

// One rung of the ladder as the choice sees it.
struct Candidate {
  ModelClass model = ModelClass::Auto;
  ModelFit fit;
  double train_rms = -1.0;  // target units
  double rss = 0.0;         // target units², summed over the matches
  double held_out = std::numeric_limits<double>::quiet_NaN();
  bool held_out_trusted = false;
  double aic = std::numeric_limits<double>::quiet_NaN();
  std::string note;  // empty: eligible
  bool eligible() const { return fit.status.ok && note.empty(); }
};

// The source points' convex hull (stored frame), counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convexHull(const Points& src) {
  std::vector<Eigen::Vector2d> p;
  for (Eigen::Index k = 0; k < src.cols(); ++k) p.emplace_back(src(0, k), src(1, k));
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 0 ? k - 1 : 0);
  return hull;
}

bool insideHull(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& x) {
  if (hull.size() < 3) return false;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
    if ((b - a).x() * (x - a).y() - (b - a).y() * (x - a).x() < 0) return false;
  }
  return true;
}

// How far two maps part between the pairs versus at them (target units): the largest distance
// on a 25×25 grid inside the pairs' convex hull, and at the pairs. An exactly determined fit
// passes through every pair whatever it does between them; a fit that bends far more between
// the pairs than it differs from the next-simpler model at them is guessing there.
std::pair<double, double> divergence(const Camera& rich, const Camera& simple, const Problem& pb) {
  const auto distance = [&](const Eigen::VectorXd& x) {
    const auto a = mapStored(rich, x), b = mapStored(simple, x);
    return a && b ? (*a - *b).norm() * pb.target_units_per_stored_unit
                  : std::numeric_limits<double>::infinity();
  };
  double at_pairs = 0.0;
  for (int k = 0; k < pb.size(); ++k) at_pairs = std::max(at_pairs, distance(pb.src.col(k)));
  const std::vector<Eigen::Vector2d> hull = convexHull(pb.src);
  const Eigen::Vector2d lo = pb.src.rowwise().minCoeff(), hi = pb.src.rowwise().maxCoeff();
  double between = at_pairs;
  constexpr int kGrid = 25;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Eigen::Vector2d x(lo.x() + (hi.x() - lo.x()) * (i + 0.5) / kGrid,
                              lo.y() + (hi.y() - lo.y()) * (j + 0.5) / kGrid);
      if (insideHull(hull, x)) between = std::max(between, distance(x));
    }
  return {between, at_pairs};
}

// Fits every rung of the ladder and scores it two ways (see chooseModel).
std::vector<Candidate> scoreLadder(const Problem& pb, const FitOptions& options) {
  std::vector<Candidate> out;
  const int m = pb.size();
  const int train_size = smallestTrainingSet(m, foldCount(m));
  for (ModelClass model : pb.ladder) {
    Candidate c;
    c.model = model;
    c.fit = fitModel(model, pb, options);
    if (!c.fit.status) {
      out.push_back(std::move(c));
      continue;
    }
    for (double e : residuals(c.fit.camera, pb)) c.rss += e * e;
    c.train_rms = std::sqrt(c.rss / m);
    if (options.diagnostics || options.model == ModelClass::Auto) {
      c.held_out = heldOutError(model, pb, options);
      // Leave-one-out of a model that needs nearly every pair mostly measures extrapolation
      // to the pair left out: trusted only when each fold trains on twice the minimum.
      c.held_out_trusted =
          !std::isnan(c.held_out) && train_size >= 2 * minimumMatches(model, pb.dimension);
    }
    out.push_back(std::move(c));
  }
  return out;
}

// The noise floor of the information criterion, in target units: the clicking precision for
// images; for object space (units unknown) a thousandth of the targets' RMS spread.
double noiseFloor(const Problem& pb, const FitOptions& options) {
  if (pb.dimension == 2) return options.click_sigma_px;
  const Eigen::VectorXd mean = pb.dst.rowwise().mean();
  const double spread = std::sqrt((pb.dst.colwise() - mean).squaredNorm() / std::max(1, pb.size()));
  return std::max(1e-3 * spread, 1e-12);
}

struct Choice {
  const Candidate* pick = nullptr;
  std::string criterion;  // "held-out" or "aic"
  std::string reason;
};

// Many matches: every rung's held-out error is trusted, and auto takes the simplest model
// whose held-out error is within options.auto_improvement of the best one.
// Few matches: leave-one-out cannot test a model that needs nearly every pair (the quadratic
// needs 9 matches; with 9 it has one residual degree of freedom). Then the models are compared
// by an information criterion with the noise known to be a click's precision σ (Mallows' Cp,
// AIC with known variance): AIC = Σ r² / σ² + 2k, k the free parameters. The small-sample AICc
// would be infinite for the quadratic on nine pairs (n − k − 1 = 0), and the estimated variance
// of an exact fit is zero (−∞ log-likelihood), so σ is fixed, not estimated. A richer model thus
// must remove more than 2σ² of squared residual per parameter it adds: a homography with
// half-pixel clicks keeps its residual near σ² per degree of freedom and stays a homography; a
// bulge the homography misses by pixels becomes the quadratic. A fit is not eligible when it
// bends between the pairs (divergence) more than three times as far as it departs from the
// next-simpler eligible model at the pairs (plus 3σ): the exact fit of a few pairs can be wild.
Choice chooseModel(std::vector<Candidate>& candidates, const Problem& pb,
                   const FitOptions& options) {
  Choice choice;
  const double sigma = noiseFloor(pb, options);
  bool all_trusted = true;
  int fitted = 0;
  for (const Candidate& c : candidates)
    if (c.fit.status) {
      ++fitted;
      all_trusted = all_trusted && c.held_out_trusted;
    }
  if (fitted == 0) return choice;
  std::ostringstream why;
  if (all_trusted) {
    choice.criterion = "held-out";
    double best = std::numeric_limits<double>::infinity();
    const Candidate* best_c = nullptr;
    for (const Candidate& c : candidates)
      if (c.eligible() && std::max(c.held_out, kExactError) < best) {
        best = std::max(c.held_out, kExactError);
        best_c = &c;
      }
    // No finite held-out error (an overflowing match): no model can be judged, none is picked.
    if (!best_c) return choice;
    for (const Candidate& c : candidates)
      if (c.eligible() && std::max(c.held_out, kExactError) * options.auto_improvement <= best) {
        choice.pick = &c;
        break;
      }
    if (!choice.pick) return choice;
    why << modelClassName(choice.pick->model) << " by held-out error (" << pb.size()
        << " matches): " << threeFigures(choice.pick->held_out);
    if (best_c != choice.pick)
      why << " is within " << threeFigures(100.0 * (1.0 / options.auto_improvement - 1.0))
          << " % of " << modelClassName(best_c->model) << " " << threeFigures(best_c->held_out);
    else
      why << " is the lowest";
    if (choice.pick != &candidates.back())
      for (const Candidate& c : candidates)
        if (c.fit.status && c.model > choice.pick->model) {
          why << "; " << modelClassName(c.model) << " " << threeFigures(c.held_out);
          break;
        }
  } else {
    choice.criterion = "aic";
    const Candidate* simpler = nullptr;
    for (Candidate& c : candidates) {
      if (!c.fit.status) continue;
      c.aic = c.rss / (sigma * sigma) + 2.0 * parameterCount(c.model, pb.dimension);
      if (simpler && pb.dimension == 2) {
        const auto [between, at_pairs] = divergence(c.fit.camera, simpler->fit.camera, pb);
        if (!(between <= 3.0 * at_pairs + 3.0 * sigma))
          c.note = "bends between the pairs: " + threeFigures(between) + " px from the " +
                   std::string(modelClassName(simpler->model)) + " map inside the pairs vs " +
                   threeFigures(at_pairs) + " px at them";
      }
      if (c.eligible()) {
        simpler = &c;
        if (!choice.pick || c.aic < choice.pick->aic) choice.pick = &c;
      }
    }
    if (!choice.pick) return choice;
    // The deciding comparison: the pick against its best-scoring eligible rival.
    const Candidate* rival = nullptr;
    for (const Candidate& c : candidates)
      if (c.eligible() && &c != choice.pick && (!rival || c.aic < rival->aic)) rival = &c;
    why << modelClassName(choice.pick->model) << " by information criterion (AIC, clicks σ "
        << threeFigures(sigma) << (pb.dimension == 2 ? " px" : " units") << ", " << pb.size()
        << " matches, too few to validate every model held-out): " << threeFigures(choice.pick->aic)
        << " (RMS " << threeFigures(choice.pick->train_rms) << ")";
    if (rival)
      why << " vs " << modelClassName(rival->model) << " " << threeFigures(rival->aic) << " (RMS "
          << threeFigures(rival->train_rms) << ")";
  }
  why << "; held-out RMS:";
  for (const Candidate& c : candidates)
    if (c.fit.status)
      why << " " << modelClassName(c.model) << " "
          << (std::isnan(c.held_out) ? std::string("n/a") : threeFigures(c.held_out));
  for (const Candidate& c : candidates)
    if (c.fit.status && !c.note.empty()) why << "; " << modelClassName(c.model) << " " << c.note;
  choice.reason = why.str();
  return choice;
}

std::vector<ModelScore> scoresOf(const std::vector<Candidate>& candidates, const Problem& pb,
                                 bool held_out_criterion) {
  std::vector<ModelScore> out;
  for (const Candidate& c : candidates) {
    ModelScore s;
    s.model = std::string(modelClassName(c.model));
    if (c.fit.status) {
      s.rms_px = c.train_rms;
      if (!std::isnan(c.held_out)) s.held_out_rms_px = c.held_out;
      const double v = held_out_criterion ? c.held_out : c.aic;
      if (std::isfinite(v)) s.criterion = v;
      s.note = c.note;
    } else {
      s.note = pb.size() < minimumMatches(c.model, pb.dimension)
                   ? "needs " + std::to_string(minimumMatches(c.model, pb.dimension)) + " matches"
                   : c.fit.status.message;
    }
    out.push_back(std::move(s));
  }
  return out;
}

FitSummary solve(const Problem& pb, const FitOptions& options) {
  FitSummary summary;
  ModelClass chosen = options.model;
  ModelFit fit;
  double held_out = std::numeric_limits<double>::quiet_NaN();
  const bool in_ladder =
      std::find(pb.ladder.begin(), pb.ladder.end(), options.model) != pb.ladder.end();
  // Auto scores the whole ladder; a named model does too (for the report) while that is cheap:
  // with held-out folds for every model the score costs several fits, which a drag among
  // hundreds of pairs refits on every mouse move (measured: edit-to-preview 0.16 → 1.07 s at
  // 300 pairs with the bound at 300).
  constexpr int kScoreNamedUpTo = 60;
  const bool score = options.model == ModelClass::Auto ||
                     (in_ladder && options.diagnostics && pb.size() <= kScoreNamedUpTo);
  std::vector<Candidate> candidates;
  Choice choice;
  if (score) {
    candidates = scoreLadder(pb, options);
    choice = chooseModel(candidates, pb, options);
    summary.record.models = scoresOf(candidates, pb, choice.criterion == "held-out");
    summary.record.criterion = choice.criterion;
  }
  if (options.model == ModelClass::Auto) {
    if (!choice.pick) {
      for (const Candidate& c : candidates)
        if (!c.fit.status) {
          summary.status = c.fit.status;
          return summary;
        }
      summary.status = Status::failure("no model of the ladder fitted these matches");
      return summary;
    }
    fit = choice.pick->fit;
    chosen = choice.pick->model;
    held_out = choice.pick->held_out;
    summary.record.reason = "auto chose " + choice.reason;
  } else if (!in_ladder) {
    fit.status = Status::failure("the " + std::string(modelClassName(options.model)) +
                                 " model is not available in " + std::to_string(pb.dimension) + "D");
  } else if (score) {
    for (const Candidate& c : candidates)
      if (c.model == options.model) {
        fit = c.fit;
        held_out = c.held_out;
      }
    summary.record.reason = std::string(modelClassName(options.model)) + " chosen by hand";
    if (choice.pick)
      summary.record.reason += "; auto would choose " + choice.reason;
  } else {
    fit = fitModel(options.model, pb, options);
    if (fit.status && options.diagnostics && pb.size() <= 2000)
      held_out = heldOutError(options.model, pb, options);
  }
  if (!fit.status) {
    summary.status = fit.status;
    return summary;
  }
  summary.camera = fit.camera;
  summary.record.model = std::string(modelClassName(chosen));
  summary.record.matches = pb.size();
  summary.record.residuals_px = residuals(fit.camera, pb);
  summary.record.rms_px = rms(summary.record.residuals_px);
  summary.record.max_px = *std::max_element(summary.record.residuals_px.begin(),
                                            summary.record.residuals_px.end());
  for (Eigen::Index i = 0; i < std::min<Eigen::Index>(3, fit.singular_values.size()); ++i)
    summary.record.singular_values.push_back(fit.singular_values[i]);
  if (!fit.note.empty())
    summary.record.reason += (summary.record.reason.empty() ? "" : "; ") + fit.note;
  if (!std::isnan(held_out)) summary.record.held_out_rms_px = held_out;
  if (fit.algebraic_rms >= 0)
    summary.record.algebraic_rms_px = fit.algebraic_rms * pb.target_units_per_stored_unit;
  if (pb.dimension == 2) {
    summary.record.pole_checked = true;
    summary.record.pole_free = fit.poles.pole_free;
    summary.record.pole_margin = fit.poles.margin;
  }
  return summary;
}

// Checks the enabled matches and collects them; an empty message means all is well.
std::string collect(const std::vector<PointMatch>& matches, int dimension,
                    std::vector<const PointMatch*>& used) {
  used.reserve(matches.size());
  for (size_t k = 0; k < matches.size(); ++k) {
    const PointMatch& match = matches[k];
    if (!match.enabled) continue;
    if (match.source.size() != dimension || match.target.size() != dimension)
      return "match " + std::to_string(k + 1) + " is not a " + std::to_string(dimension) + "D match";
    if (!match.source.allFinite() || !match.target.allFinite())
      return "match " + std::to_string(k + 1) + " has a non-finite coordinate";
    used.push_back(&match);
  }
  return used.empty() ? "no enabled matches" : "";
}

}  // namespace

std::string_view modelClassName(ModelClass model) {
  switch (model) {
    case ModelClass::Auto: return "auto";
    case ModelClass::Translation: return "translation";
    case ModelClass::Similarity: return "similarity";
    case ModelClass::Affine: return "affine";
    case ModelClass::Homography: return "homography";
    case ModelClass::Quadratic: return "quadratic";
  }
  return "unknown";
}

std::optional<ModelClass> modelClassFromName(std::string_view name) {
  for (ModelClass m : {ModelClass::Auto, ModelClass::Translation, ModelClass::Similarity,
                       ModelClass::Affine, ModelClass::Homography, ModelClass::Quadratic})
    if (name == modelClassName(m)) return m;
  return std::nullopt;
}

int minimumMatches(ModelClass model, int dimension) {
  const int n = dimension + 1;
  switch (model) {
    case ModelClass::Translation: return 1;
    case ModelClass::Similarity: return 2;
    case ModelClass::Affine: return dimension + 1;
    case ModelClass::Homography: return dimension + 2;
    case ModelClass::Quadratic: {
      // n²(n+1)/2 unknowns up to scale, n - 1 equations per match (paper §4).
      const int unknowns = n * n * (n + 1) / 2 - 1;
      return (unknowns + n - 2) / (n - 1);
    }
    case ModelClass::Auto: return 1;
  }
  return 1;
}

std::vector<double> reprojectionResiduals(const Camera& camera,
                                          const std::vector<PointMatch>& matches) {
  std::vector<double> out;
  out.reserve(matches.size());
  for (const PointMatch& match : matches) {
    const auto y = targetPixelFromSourcePixel(camera, match.source.head<2>());
    out.push_back(y ? (*y - match.target.head<2>()).norm() : std::numeric_limits<double>::infinity());
  }
  return out;
}

std::string FitSummary::report() const {
  if (!status) return "fit failed: " + status.message;
  const int p = camera.layout().find(BlockKind::Position);
  const char* units = p >= 0 && camera.blocks()[p].size == 4 ? " units" : " px";
  std::ostringstream s;
  s << record.model << ", " << record.matches << " matches, RMS " << threeFigures(record.rms_px)
    << units << ", max " << threeFigures(record.max_px) << units;
  return s.str();
}

Status FitOptions::check(const FieldNames& names) const {
  using Ends = OptionsCheck::Ends;
  constexpr double kNoBound = OptionsCheck::kNoBound;
  return OptionsCheck(names)
      .oneOf("model", modelClassName(model) != "unknown",
             "auto, translation, similarity, affine, homography or quadratic",
             static_cast<int>(model))
      .number("auto_improvement", auto_improvement, 0.0, 1.0, Ends::AboveMin)
      .number("click_sigma_px", click_sigma_px, 0.0, kNoBound, Ends::AboveMin)
      .whole("restarts", restarts, 0, 1000)
      .number("robust_threshold_px", robust_threshold_px, 0.0, kNoBound, Ends::AboveMin)
      .status();
}

FitSummary fitImageCamera(const std::vector<PointMatch>& matches, FrameSize source_size,
                          FrameSize target_size, const FitOptions& options) {
  if (const Status s = options.check(); !s) {
    FitSummary summary;
    summary.status = s;
    return summary;
  }
  if (!source_size.isImage() || !target_size.isImage()) {
    FitSummary summary;
    summary.status = Status::failure("the source and target frame sizes must be positive");
    return summary;
  }
  std::vector<const PointMatch*> used;
  if (const std::string error = collect(matches, 2, used); !error.empty()) {
    FitSummary summary;
    summary.status = Status::failure(error);
    return summary;
  }
  if (options.robust) {
    // Find the inliers, fit them as usual, and report every enabled match's residual.
    std::vector<PointMatch> enabled;
    for (const PointMatch* match : used) enabled.push_back(*match);
    RobustOptions ro;
    ro.threshold_px = options.robust_threshold_px;
    const RobustResult inl = findInliers(enabled, source_size, target_size, options.model, ro);
    if (!inl.status) {
      FitSummary summary;
      summary.status = inl.status;
      return summary;
    }
    std::vector<PointMatch> kept;
    for (int k : inl.inliers) kept.push_back(enabled[k]);
    FitOptions plain = options;
    plain.robust = false;
    FitSummary summary = fitImageCamera(kept, source_size, target_size, plain);
    if (!summary.status) return summary;
    summary.record.inliers = inl.inliers;
    summary.record.residuals_px = reprojectionResiduals(summary.camera, enabled);
    summary.record.reason += std::string(summary.record.reason.empty() ? "" : "; ") +
                             "robust: " + std::to_string(inl.inliers.size()) + " of " +
                             std::to_string(enabled.size()) + " matches within " +
                             threeFigures(options.robust_threshold_px) + " px after " +
                             std::to_string(inl.iterations) + " iterations";
    return summary;
  }
  Problem pb;
  pb.dimension = 2;
  pb.src.resize(2, static_cast<Eigen::Index>(used.size()));
  pb.dst.resize(2, static_cast<Eigen::Index>(used.size()));
  // normalizedFromPixel (frames.h), u_n = (u - w/2) / s with s = max(w, h) / 2, inlined with
  // the reciprocal (equal to round-off): this loop touches every match.
  const double src_inv = 2.0 / std::max(source_size.width, source_size.height);
  const double dst_inv = 2.0 / std::max(target_size.width, target_size.height);
  const double scx = source_size.width / 2.0, scy = source_size.height / 2.0;
  const double dcx = target_size.width / 2.0, dcy = target_size.height / 2.0;
  for (Eigen::Index k = 0; k < pb.src.cols(); ++k) {
    const Eigen::VectorXd& s = used[k]->source;
    const Eigen::VectorXd& t = used[k]->target;
    pb.src(0, k) = (s[0] - scx) * src_inv;
    pb.src(1, k) = (s[1] - scy) * src_inv;
    pb.dst(0, k) = (t[0] - dcx) * dst_inv;
    pb.dst(1, k) = (t[1] - dcy) * dst_inv;
  }
  pb.target_units_per_stored_unit = std::max(target_size.width, target_size.height) / 2.0;
  pb.frame_lo = normalizedFromPixel(source_size, {0.0, 0.0});
  pb.frame_hi = normalizedFromPixel(source_size, {static_cast<double>(source_size.width),
                                                  static_cast<double>(source_size.height)});
  pb.make_camera = [&](const std::vector<Eigen::MatrixXd>& q) {
    return Camera({Block{BlockKind::Position, 3}}, {Stage{q}}, source_size, target_size);
  };
  pb.ladder = {ModelClass::Translation, ModelClass::Similarity, ModelClass::Affine,
               ModelClass::Homography, ModelClass::Quadratic};
  return solve(pb, options);
}

FitSummary fitObjectCamera(const std::vector<PointMatch>& matches, const FitOptions& options) {
  if (const Status s = options.check(); !s) {
    FitSummary summary;
    summary.status = s;
    return summary;
  }
  std::vector<const PointMatch*> used;
  if (const std::string error = collect(matches, 3, used); !error.empty()) {
    FitSummary summary;
    summary.status = Status::failure(error);
    return summary;
  }
  Problem pb;
  pb.dimension = 3;
  pb.src.resize(3, static_cast<Eigen::Index>(used.size()));
  pb.dst.resize(3, static_cast<Eigen::Index>(used.size()));
  for (Eigen::Index k = 0; k < pb.src.cols(); ++k) {
    pb.src.col(k) = used[k]->source;
    pb.dst.col(k) = used[k]->target;
  }
  pb.make_camera = [](const std::vector<Eigen::MatrixXd>& q) {
    return Camera({Block{BlockKind::Position, 4}}, {Stage{q}}, {}, {});
  };
  pb.ladder = {ModelClass::Translation, ModelClass::Affine, ModelClass::Homography,
               ModelClass::Quadratic};
  return solve(pb, options);
}

}  // namespace artcam
