// SPDX-License-Identifier: Apache-2.0
#include "core/fit/fit_colour.h"

#include "core/colour/colour_difference.h"
#include "core/fit/cross_validation.h"
#include "core/fit/dlt.h"
#include "core/fit/fit_image.h"
#include "core/fit/msac.h"
#include "core/fit/normalize.h"
#include "core/fit/report_format.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

namespace artcam {
namespace {

// Held-out errors below this (ΔE00) are "exact": differences there are rounding.
constexpr double kExactDeltaE = 1e-6;
// Relative singular value below which a design matrix counts as rank deficient.
constexpr double kRankTolerance = 1e-9;
constexpr ColourModel kLadder[] = {ColourModel::Linear, ColourModel::Affine,
                                   ColourModel::RootPolynomial, ColourModel::Quadratic};

struct Samples {
  std::vector<Eigen::Vector3d> src, dst;
  int size() const { return static_cast<int>(src.size()); }
  Samples subset(const std::vector<int>& keep) const {
    Samples s;
    for (int k : keep) {
      s.src.push_back(src[k]);
      s.dst.push_back(dst[k]);
    }
    return s;
  }
};

struct Fitted {
  Status status;
  ColourMap map;
};

std::string name(ColourModel model) { return std::string(colourModelName(model)); }

std::string tooFew(ColourModel model, int have) {
  const int need = minimumColourSamples(model);
  const int more = need - have;
  return std::to_string(have) + " colour sample" + (have == 1 ? "" : "s") + "; the " + name(model) +
         " colour model needs at least " + std::to_string(need) + " (" + std::to_string(more) +
         " more sample" + (more == 1 ? "" : "s") + " of different colours would determine it)";
}

// Linear least squares in the model's terms (linear, affine, root-polynomial), by SVD.
Fitted fitTerms(ColourModel model, const Samples& s) {
  Fitted out;
  out.map.model = model;
  const int m = s.size();
  if (m < minimumColourSamples(model)) {
    out.status = Status::failure(tooFew(model, m));
    return out;
  }
  const bool affine = model == ColourModel::Affine;
  // Affine: condition like geometry (centroid to the origin, RMS √3); the others keep the
  // origin (black maps to black) and scale each column to unit RMS instead.
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  if (affine) {
    Points pts(3, m);
    for (int k = 0; k < m; ++k) pts.col(k) = s.src[k];
    t = conditioningTransform(pts);
  }
  const Eigen::Index terms = colourTerms(model, Eigen::Vector3d::Zero()).size();
  Eigen::MatrixXd a(m, terms), b(m, 3);
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector3d x = affine ? Eigen::Vector3d(t.topLeftCorner<3, 3>() * s.src[k] +
                                                       t.topRightCorner<3, 1>())
                                     : s.src[k];
    a.row(k) = colourTerms(model, x).transpose();
    b.row(k) = s.dst[k].transpose();
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(terms);
  if (!affine)
    for (Eigen::Index j = 0; j < terms; ++j) {
      const double rms = a.col(j).norm() / std::sqrt(static_cast<double>(m));
      if (rms > 0.0) scale[j] = rms;
    }
  const Eigen::MatrixXd scaled = a * scale.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  if (!(sv[sv.size() - 1] > kRankTolerance * sv[0])) {
    out.status = Status::failure(
        "the " + std::to_string(m) + " source colours do not determine the " + name(model) +
        " colour model (its design matrix is rank deficient: the colours are too alike, e.g. all "
        "grey or all on one line through black); add samples of other hues");
    return out;
  }
  const Eigen::MatrixXd x = scale.cwiseInverse().asDiagonal() * svd.solve(b);  // terms × 3
  out.map.m = x.transpose();
  if (affine) out.map.m = out.map.m * t;  // undo the conditioning: dst = M' T (r, g, b, 1)ᵀ
  if (!out.map.m.allFinite()) out.status = Status::failure("the " + name(model) + " fit is not finite");
  return out;
}

// The colour box the map must behave on: the unit cube and every sample's source colour.
void colourBox(const Samples& s, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo = Eigen::Vector3d::Zero();
  hi = Eigen::Vector3d::Ones();
  for (const Eigen::Vector3d& c : s.src) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
}

// Scales the map so its denominator is ≥ 1 over the colour box (the output alpha, the colour
// block's weight of eq 5, then clamps to 1 for every opaque colour in the box); false when the
// denominator changes sign there (a pole).
bool scalePoleFree(ColourMap& map, const Samples& s) {
  Eigen::Vector3d lo, hi;
  colourBox(s, lo, hi);
  const QuadraticRange range = quadraticRangeOverBox(map.q[3], lo, hi);
  double scale = 0.0;
  if (range.least > 0.0) scale = range.least;
  else if (range.greatest < 0.0) scale = range.greatest;
  if (scale == 0.0 || !std::isfinite(1.0 / scale)) return false;
  for (Eigen::Matrix4d& q : map.q) q /= scale;
  return true;
}

// The quadratic preferring a flat denominator. When the samples are nearly explained by a map
// of lower degree (a linear map with a bend near white, say), N_c = f_c·L fits about as well for
// any affine L: the DLT's near-null space has several directions and the plain solution picks
// one at random, its denominator often crossing zero inside the box. Adding λ·|d'|² to the
// conditioned DLT cost, d' the denominator's non-constant coefficients, picks the member with
// the flattest denominator; λ grows (relative to the normal matrix's mean eigenvalue) until the
// map is pole-free. The samples' fit still decides everything the data determine.
std::optional<ColourMap> flatDenominatorQuadratic(const Samples& s) {
  const Eigen::Index m = s.size();
  Points src(3, m), dst(3, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    src.col(k) = s.src[static_cast<size_t>(k)];
    dst.col(k) = s.dst[static_cast<size_t>(k)];
  }
  const Eigen::MatrixXd ts = conditioningTransform(src), td = conditioningTransform(dst);
  const Eigen::MatrixXd normal = quadraticNormal3d(applyTransform(ts, src), applyTransform(td, dst));
  const double mean_eigenvalue = normal.trace() / 40.0;
  const Eigen::MatrixXd td_inv = td.inverse();
  for (double relative : {1e-8, 1e-6, 1e-4, 1e-3, 1e-2}) {
    Eigen::MatrixXd penalised = normal;
    for (int i = 30; i < 39; ++i) penalised(i, i) += relative * mean_eigenvalue;  // not (3,3)
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(penalised);
    const Eigen::VectorXd r = eig.eigenvectors().col(0);
    std::array<Eigen::Matrix4d, 4> conditioned;
    for (int i = 0; i < 4; ++i) {
      int c = 10 * i;
      for (int j = 0; j < 4; ++j)
        for (int l = j; l < 4; ++l) conditioned[i](j, l) = conditioned[i](l, j) = r[c++];
    }
    // Undo the conditioning as fit_image.cpp does: Q ← tsᵀ Q ts, then mix by td⁻¹.
    ColourMap map;
    map.model = ColourModel::Quadratic;
    for (int i = 0; i < 4; ++i) {
      map.q[i].setZero();
      for (int j = 0; j < 4; ++j) map.q[i] += td_inv(i, j) * (ts.transpose() * conditioned[j] * ts);
    }
    bool finite = true;
    for (const Eigen::Matrix4d& q : map.q) finite = finite && q.allFinite();
    if (finite && scalePoleFree(map, s)) return map;
  }
  return std::nullopt;
}

// The paper's §4 DLT on the colour block: the 3D quadratic solver of fit_image.h. Minimal sets
// inside the robust search skip the pole test (`check_pole` false): such a map still scores
// the samples, and the final fit on the inliers is checked. A map with a pole is fitted again
// preferring a flat denominator (flatDenominatorQuadratic) before it is refused.
Fitted fitQuadratic(const Samples& s, bool check_pole = true) {
  Fitted out;
  out.map.model = ColourModel::Quadratic;
  if (s.size() < minimumColourSamples(ColourModel::Quadratic)) {
    out.status = Status::failure(tooFew(ColourModel::Quadratic, s.size()));
    return out;
  }
  std::vector<PointMatch> matches;
  matches.reserve(s.src.size());
  for (int k = 0; k < s.size(); ++k) matches.push_back({s.src[k], s.dst[k], true});
  FitOptions fo;
  fo.model = ModelClass::Quadratic;
  fo.diagnostics = false;
  const FitSummary fit = fitObjectCamera(matches, fo);
  if (!fit.status) {
    out.status = Status::failure("quadratic colour model: " + fit.status.message);
    return out;
  }
  for (int i = 0; i < 4; ++i) out.map.q[i] = fit.camera.stages()[0].q[i];
  if (!check_pole) return out;
  if (scalePoleFree(out.map, s)) return out;
  if (const auto flat = flatDenominatorQuadratic(s)) {
    out.map = *flat;
    return out;
  }
  Eigen::Vector3d lo, hi;
  colourBox(s, lo, hi);
  out.status = Status::failure(
      "the quadratic colour map fitted to these samples has a pole: its denominator changes "
      "sign inside the colour box [" +
      threeFigures(lo.minCoeff()) + ", " + threeFigures(hi.maxCoeff()) +
      "]; a simpler model, or more samples spread over the gamut, avoids it");
  return out;
}

Fitted fitModel(ColourModel model, const Samples& s, bool check_pole = true) {
  return model == ColourModel::Quadratic ? fitQuadratic(s, check_pole) : fitTerms(model, s);
}

// ΔE00 of each sample; infinity where the map does not map it.
std::vector<double> deltaEs(const ColourMap& map, const Samples& s) {
  std::vector<double> out;
  out.reserve(s.src.size());
  for (int k = 0; k < s.size(); ++k) {
    const auto y = map.apply(s.src[k]);
    out.push_back(y ? deltaE2000(s.dst[k], *y) : std::numeric_limits<double>::infinity());
  }
  return out;
}

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

// K-fold held-out mean ΔE00 (cross_validation.h; leave-one-out up to 10 samples); NaN when a
// fold leaves too few samples or a fold's fit fails.
double heldOut(ColourModel model, const Samples& s) {
  const int m = s.size();
  const auto sum =
      crossValidatedSum(m, std::min(m, 10), minimumColourSamples(model),
                        [&](const std::vector<int>& train,
                            const std::vector<int>& held) -> std::optional<std::vector<double>> {
                          const Fitted fit = fitModel(model, s.subset(train));
                          if (!fit.status) return std::nullopt;
                          return deltaEs(fit.map, s.subset(held));
                        });
  return sum ? *sum / m : std::numeric_limits<double>::quiet_NaN();
}

// The simplest candidate whose held-out error a richer one does not beat by `improvement`,
// among those `allowed`; nullptr when none was validated.
const ColourCandidate* select(const std::vector<ColourCandidate>& cs, double improvement,
                              bool representable_only) {
  const auto allowed = [&](const ColourCandidate& c) {
    return c.fitted && c.held_out_de >= 0.0 && (!representable_only || isQuadraticForm(c.model));
  };
  double best = std::numeric_limits<double>::infinity();
  for (const ColourCandidate& c : cs)
    if (allowed(c)) best = std::min(best, std::max(c.held_out_de, kExactDeltaE));
  for (const ColourCandidate& c : cs)
    if (allowed(c) && std::max(c.held_out_de, kExactDeltaE) * improvement <= best) return &c;
  return nullptr;
}

// Fits the requested model, or runs the selection (auto), on these samples.
ColourFitSummary fitOrSelect(const Samples& s, const ColourFitOptions& options) {
  ColourFitSummary summary;
  if (options.model != ColourModel::Auto) {
    const Fitted fit = fitModel(options.model, s);
    if (!fit.status) {
      summary.status = fit.status;
      return summary;
    }
    summary.map = fit.map;
    summary.selected = options.model;
    summary.stored = isQuadraticForm(options.model);
    if (options.diagnostics) {
      const double h = heldOut(options.model, s);
      if (!std::isnan(h)) summary.held_out_de = h;
    }
    return summary;
  }
  std::vector<Fitted> fits;
  for (ColourModel model : kLadder) {
    ColourCandidate c;
    c.model = model;
    Fitted f = fitModel(model, s);
    c.fitted = static_cast<bool>(f.status);
    if (c.fitted) {
      c.mean_de = mean(deltaEs(f.map, s));
      const double h = heldOut(model, s);
      if (!std::isnan(h)) c.held_out_de = h;
    } else {
      c.failure = f.status.message;
    }
    summary.candidates.push_back(c);
    fits.push_back(std::move(f));
  }
  const ColourCandidate* winner = select(summary.candidates, options.auto_improvement, false);
  const ColourCandidate* stored = select(summary.candidates, options.auto_improvement, true);
  if (!stored) {
    // Nothing validated (too few samples for any fold): the simplest representable fit.
    for (const ColourCandidate& c : summary.candidates)
      if (c.fitted && isQuadraticForm(c.model)) {
        stored = &c;
        break;
      }
  }
  if (!stored) {
    summary.status = Status::failure("no colour model could be fitted: " +
                                     summary.candidates.front().failure);
    return summary;
  }
  const size_t index = static_cast<size_t>(stored - summary.candidates.data());
  summary.map = fits[index].map;
  summary.selected = winner ? winner->model : stored->model;
  summary.held_out_de = stored->held_out_de;
  std::ostringstream why;
  why << "auto chose " << colourModelName(stored->model) << "; held-out mean dE00:";
  for (const ColourCandidate& c : summary.candidates)
    why << " " << colourModelName(c.model) << " "
        << (!c.fitted           ? std::string("refused")
            : c.held_out_de < 0 ? std::string("n/a")
                                : threeFigures(c.held_out_de));
  if (winner && winner->model != stored->model)
    why << "; root-polynomial did best but is not a quadratic form (its sqrt(rg) terms), so the "
           "camera holds the best representable model, "
        << colourModelName(stored->model);
  summary.reason = why.str();
  return summary;
}

// MSAC with local optimisation over minimal sets (msac.h, as robust.h), scored by ΔE00. A named
// model samples its own minimal sets. Auto samples the affine model (4 samples: a 13-sample
// quadratic minimal set is rarely outlier-free and fits noise wildly) and lets the local
// optimisation re-fit both the affine and, given twice its minimum of inliers, the quadratic
// model on the inliers, keeping whichever scores better: non-linear data then keeps its
// extreme colours as inliers.
Status findColourInliers(const Samples& s, const ColourFitOptions& options, std::vector<int>& inliers,
                         int& iterations) {
  const int m = s.size();
  const bool auto_model = options.model == ColourModel::Auto;
  const ColourModel sampled = auto_model ? ColourModel::Affine : options.model;
  const int k = minimumColourSamples(sampled);
  const int quadratic_from = 2 * minimumColourSamples(ColourModel::Quadratic);
  if (m < k)
    return Status::failure("robust fitting of the " + name(sampled) + " colour model needs at least " +
                           std::to_string(k) + " samples, have " + std::to_string(m));
  const double t2 = options.robust_threshold_de * options.robust_threshold_de;
  const auto score = [&](const ColourMap& map) {
    MsacScore sc;
    const std::vector<double> e = deltaEs(map, s);
    for (int j = 0; j < m; ++j) sc.add(j, e[j] * e[j], t2);
    return sc;
  };
  const auto fit_sample = [&](const std::vector<int>& sample) -> std::optional<MsacScore> {
    const Fitted fit = fitModel(sampled, s.subset(sample), false);
    if (!fit.status) return std::nullopt;
    return score(fit.map);
  };
  // The better scoring of the sampled model and, for auto with enough inliers, the quadratic.
  const auto refit = [&](const std::vector<int>& in) -> std::optional<MsacScore> {
    std::optional<MsacScore> next;
    for (ColourModel model : {sampled, ColourModel::Quadratic}) {
      if (model == ColourModel::Quadratic &&
          (!auto_model || static_cast<int>(in.size()) < quadratic_from))
        continue;
      const Fitted fit = fitModel(model, s.subset(in));
      if (!fit.status) continue;
      MsacScore t = score(fit.map);
      if (!next || t.cost < next->cost) next = std::move(t);
    }
    return next;
  };
  MsacOptions search;
  search.confidence = options.robust_confidence;
  search.max_iterations = options.robust_max_iterations;
  search.seed = options.robust_seed;
  MsacResult best = runMsac({m, k, fit_sample, refit}, search);
  iterations = best.iterations;
  if (static_cast<int>(best.inliers.size()) < k)
    return Status::failure("no " + name(sampled) + " colour map explains more than " +
                           std::to_string(best.inliers.size()) + " of the " + std::to_string(m) +
                           " samples within dE00 " + threeFigures(options.robust_threshold_de));
  inliers = std::move(best.inliers);
  return Status::success();
}

}  // namespace

Status ColourFitOptions::check(const FieldNames& names) const {
  using Ends = OptionsCheck::Ends;
  return OptionsCheck(names)
      .oneOf("model", colourModelName(model) != "unknown",
             "auto, linear, affine, root-polynomial or quadratic", static_cast<int>(model))
      .number("auto_improvement", auto_improvement, 0.0, 1.0, Ends::AboveMin)
      .number("robust_threshold_de", robust_threshold_de, 0.0, OptionsCheck::kNoBound,
              Ends::AboveMin)
      .number("robust_confidence", robust_confidence, 0.0, 1.0, Ends::AboveMin)
      .whole("robust_max_iterations", robust_max_iterations, 1, 10000000)
      .status();
}

ColourFitSummary fitColourSamples(const std::vector<PointMatch>& samples,
                                  const ColourFitOptions& options) {
  ColourFitSummary summary;
  if (const Status s = options.check(); !s) {
    summary.status = s;
    return summary;
  }
  Samples s;
  for (size_t k = 0; k < samples.size(); ++k) {
    const PointMatch& p = samples[k];
    if (!p.enabled) continue;
    if (p.source.size() != 3 || p.target.size() != 3) {
      summary.status = Status::failure("sample " + std::to_string(k + 1) + " is not a pair of RGB colours");
      return summary;
    }
    if (!p.source.allFinite() || !p.target.allFinite()) {
      summary.status = Status::failure("sample " + std::to_string(k + 1) + " has a non-finite value");
      return summary;
    }
    s.src.emplace_back(p.source);
    s.dst.emplace_back(p.target);
  }
  if (s.size() == 0) {
    summary.status = Status::failure("no enabled colour samples");
    return summary;
  }
  std::string robust_note;
  if (options.robust) {
    std::vector<int> inliers;
    int iterations = 0;
    if (const Status st = findColourInliers(s, options, inliers, iterations); !st) {
      summary.status = st;
      return summary;
    }
    ColourFitOptions plain = options;
    plain.robust = false;
    summary = fitOrSelect(s.subset(inliers), plain);
    summary.inliers = inliers;
    robust_note = "robust: " + std::to_string(inliers.size()) + " of " + std::to_string(s.size()) +
                  " samples within dE00 " + threeFigures(options.robust_threshold_de) + " after " +
                  std::to_string(iterations) + " iterations";
  } else {
    summary = fitOrSelect(s, options);
  }
  if (!summary.status) return summary;
  summary.delta_e = deltaEs(summary.map, s);
  summary.mean_de = mean(summary.delta_e);
  summary.max_de = *std::max_element(summary.delta_e.begin(), summary.delta_e.end());
  std::vector<double> sorted = summary.delta_e;
  std::sort(sorted.begin(), sorted.end());
  const size_t n = sorted.size();
  summary.median_de = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  double sq = 0.0;
  for (int k = 0; k < s.size(); ++k) {
    const auto y = summary.map.apply(s.src[k]);
    sq += y ? (*y - s.dst[k]).squaredNorm() : std::numeric_limits<double>::infinity();
  }
  summary.rms_rgb = std::sqrt(sq / s.size());
  if (!robust_note.empty())
    summary.reason += std::string(summary.reason.empty() ? "" : "; ") + robust_note;
  return summary;
}

std::string ColourFitSummary::report() const {
  if (!status) return "colour fit failed: " + status.message;
  std::ostringstream out;
  out << colourModelName(map.model) << " colour map, " << delta_e.size() << " samples, dE00 mean "
      << threeFigures(mean_de) << ", median " << threeFigures(median_de) << ", max "
      << threeFigures(max_de);
  return out.str();
}

FitRecord ColourFitSummary::record() const {
  FitRecord r;
  r.model = std::string(colourModelName(map.model));
  r.matches = static_cast<int>(delta_e.size());
  r.residuals_px = delta_e;
  double sq = 0.0;
  for (double e : delta_e) sq += e * e;
  r.rms_px = delta_e.empty() ? 0.0 : std::sqrt(sq / static_cast<double>(delta_e.size()));
  r.max_px = max_de;
  r.reason =
      "colour block fitted to colour samples; residuals are CIEDE2000 dE00, not pixels "
      "(mean " +
      threeFigures(mean_de) + ", median " + threeFigures(median_de) + ")";
  if (held_out_de >= 0) r.reason += "; held-out mean dE00 " + threeFigures(held_out_de);
  if (!reason.empty()) r.reason += "; " + reason;
  r.inliers = inliers;
  return r;
}

}  // namespace artcam
