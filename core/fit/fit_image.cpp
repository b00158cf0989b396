#include "core/fit/fit_image.h"

#include "core/fit/dlt.h"
#include "core/fit/normalize.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace artcam {

namespace {

constexpr std::array<ModelClass, 5> kLadder = {ModelClass::Translation, ModelClass::Similarity,
                                                ModelClass::Affine, ModelClass::Homography,
                                                ModelClass::Quadratic};
// Held-out errors below this are "exact" (pixels): differences there are rounding, not fit.
constexpr double kExactPx = 1e-6;

struct Points {
  std::vector<Eigen::Vector2d> src;  // normalised source frame
  std::vector<Eigen::Vector2d> dst;  // normalised target frame
};

struct ModelFit {
  Status status;
  Camera camera;
  Eigen::VectorXd singular_values;
  std::string note;
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string moreMatches(int have, int need) {
  const int more = need - have;
  return std::to_string(more) + " more well-spread match" + (more == 1 ? "" : "es") +
         " would determine it";
}

// Scale so the largest entry is 1 and the denominator is positive at the frame centre: the
// same camera, written the same way whichever null vector sign the SVD returned.
void canonicalise(std::array<Eigen::Matrix3d, 3>& q) {
  double scale = 0.0;
  for (const Eigen::Matrix3d& m : q) scale = std::max(scale, m.cwiseAbs().maxCoeff());
  if (q[2](2, 2) < 0.0) scale = -scale;
  if (scale != 0.0)
    for (Eigen::Matrix3d& m : q) m /= scale;
}

ModelFit fitModel(ModelClass model, const Points& pts, FrameSize source_size,
                  FrameSize target_size, bool condition) {
  ModelFit out;
  const int m = static_cast<int>(pts.src.size());
  const int need = minimumMatches(model);
  const std::string name(modelClassName(model));
  if (m < need) {
    out.status = Status::failure(std::to_string(m) + " match" + (m == 1 ? "" : "es") + "; the " +
                                 name + " model needs at least " + std::to_string(need) + " (" +
                                 moreMatches(m, need) + ")");
    return out;
  }
  const int distinct = countDistinct(pts.src);
  if (distinct < need) {
    out.status = Status::failure("only " + std::to_string(distinct) +
                                 " distinct source points among " + std::to_string(m) +
                                 " matches; the " + name + " model needs " + std::to_string(need) +
                                 " (" + moreMatches(distinct, need) + ")");
    return out;
  }
  const bool needs_2d_spread = model != ModelClass::Translation && model != ModelClass::Similarity;
  if (needs_2d_spread && collinearity(pts.src) < 1e-7) {
    out.status = Status::failure("all " + std::to_string(m) +
                                 " source points lie on one line; the " + name +
                                 " model needs points spread over the image");
    return out;
  }

  const bool use_conditioning = condition && model != ModelClass::Translation;
  const Eigen::Matrix3d ts = use_conditioning ? conditioningTransform(pts.src) : Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d td = use_conditioning ? conditioningTransform(pts.dst) : Eigen::Matrix3d::Identity();
  const std::vector<Eigen::Vector2d> src = applyTransform(ts, pts.src);
  const std::vector<Eigen::Vector2d> dst = applyTransform(td, pts.dst);

  if (model == ModelClass::Quadratic && conicDegeneracy(src) < 1e-9) {
    out.status = Status::failure("all " + std::to_string(m) +
                                 " source points lie on one conic (such as a circle or two "
                                 "lines), so the quadratic model is not determined; add matches "
                                 "off that curve");
    return out;
  }

  DltSolution s;
  switch (model) {
    case ModelClass::Translation: s = solveTranslation(src, dst); break;
    case ModelClass::Similarity: s = solveSimilarity(src, dst); break;
    case ModelClass::Affine: s = solveAffine(src, dst); break;
    case ModelClass::Homography: s = solveHomographyDlt(src, dst); break;
    case ModelClass::Quadratic:
    case ModelClass::Auto: s = solveQuadraticDlt(src, dst); break;
  }
  out.singular_values = s.singular_values;
  if (s.null_dimension > 1 && model == ModelClass::Quadratic) {
    // Exact homography data: Q_i = sym(l h_iᵀ) fits for every line l (DESIGN §2), and an
    // arbitrary null vector is 0/0 along l. Fix l to the line at infinity: the homography.
    const DltSolution h = solveHomographyDlt(src, dst);
    if (h.null_dimension == 1) {
      s = h;
      out.note = "the data are a homography (quadratic null space " +
                 std::to_string(out.singular_values.size() > 0 ? 3 : 0) +
                 "-dimensional), so l is fixed at the line at infinity";
    }
  }
  if (s.null_dimension > 1) {
    out.status = Status::failure("the matches do not determine the " + name +
                                 " model (its design matrix has a " +
                                 std::to_string(s.null_dimension) +
                                 "-dimensional null space); add well-spread matches");
    return out;
  }

  // Undo conditioning: input x_c(row) = x_n(row) tsᵀ gives Q ← tsᵀ Q ts; output y_n = td⁻¹ y_c.
  std::array<Eigen::Matrix3d, 3> q;
  const Eigen::Matrix3d td_inv = td.inverse();
  if (s.linear) {
    const Eigen::Matrix3d h = td_inv * s.h * ts;
    const std::vector<Eigen::MatrixXd> lifted = liftHomography(h);
    for (int i = 0; i < 3; ++i) q[i] = lifted[i];
  } else {
    std::array<Eigen::Matrix3d, 3> qs;
    for (int i = 0; i < 3; ++i) qs[i] = ts.transpose() * s.q[i] * ts;
    for (int i = 0; i < 3; ++i) {
      q[i].setZero();
      for (int j = 0; j < 3; ++j) q[i] += td_inv(i, j) * qs[j];
    }
  }
  canonicalise(q);
  if (!(q[0].allFinite() && q[1].allFinite() && q[2].allFinite())) {
    out.status = Status::failure("the " + name + " fit produced non-finite entries");
    return out;
  }
  out.camera = Camera::rtcam({q[0], q[1], q[2]}, source_size, target_size);
  return out;
}

double rms(const std::vector<double>& r) {
  if (r.empty()) return 0.0;
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return std::sqrt(sum / static_cast<double>(r.size()));
}

// K-fold held-out RMS error in target pixels; NaN when the folds leave too few matches.
double heldOutError(ModelClass model, const Points& pts, FrameSize source_size,
                    FrameSize target_size, bool condition) {
  const int m = static_cast<int>(pts.src.size());
  const int folds = m > 5000 ? 3 : std::min(m, 10);
  if (folds < 2 || m - (m + folds - 1) / folds < minimumMatches(model))
    return std::numeric_limits<double>::quiet_NaN();
  const double scale = std::max(target_size.width, target_size.height) / 2.0;
  double sum = 0.0;
  for (int f = 0; f < folds; ++f) {
    Points train;
    std::vector<int> held;
    for (int k = 0; k < m; ++k) {
      if (k % folds == f) {
        held.push_back(k);
      } else {
        train.src.push_back(pts.src[k]);
        train.dst.push_back(pts.dst[k]);
      }
    }
    const ModelFit fit = fitModel(model, train, source_size, target_size, condition);
    if (!fit.status) return std::numeric_limits<double>::quiet_NaN();
    for (int k : held) {
      const auto y = targetFromSourceNormalized(fit.camera, pts.src[k]);
      const double e = y ? (*y - pts.dst[k]).norm() * scale : std::numeric_limits<double>::infinity();
      sum += e * e;
    }
  }
  return std::sqrt(sum / m);
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

int minimumMatches(ModelClass model) {
  switch (model) {
    case ModelClass::Translation: return 1;
    case ModelClass::Similarity: return 2;
    case ModelClass::Affine: return 3;
    case ModelClass::Homography: return 4;
    case ModelClass::Quadratic: return 9;  // 18 unknowns up to scale, 2 equations per match
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
  std::ostringstream s;
  s << record.model << ", " << record.matches << " matches, RMS " << fmt(record.rms_px)
    << " px, max " << fmt(record.max_px) << " px";
  return s.str();
}

FitSummary fitImageCamera(const std::vector<PointMatch>& matches, FrameSize source_size,
                          FrameSize target_size, const FitOptions& options) {
  FitSummary summary;
  if (!source_size.isImage() || !target_size.isImage()) {
    summary.status = Status::failure("the source and target frame sizes must be positive");
    return summary;
  }
  std::vector<PointMatch> used;
  Points pts;
  for (size_t k = 0; k < matches.size(); ++k) {
    const PointMatch& match = matches[k];
    if (!match.enabled) continue;
    if (match.source.size() < 2 || match.target.size() < 2) {
      summary.status = Status::failure("match " + std::to_string(k + 1) + " is not a 2D match");
      return summary;
    }
    if (!match.source.head<2>().allFinite() || !match.target.head<2>().allFinite()) {
      summary.status =
          Status::failure("match " + std::to_string(k + 1) + " has a non-finite coordinate");
      return summary;
    }
    used.push_back(match);
    pts.src.push_back(normalizedFromPixel(source_size, match.source.head<2>()));
    pts.dst.push_back(normalizedFromPixel(target_size, match.target.head<2>()));
  }
  if (used.empty()) {
    summary.status = Status::failure("no enabled matches");
    return summary;
  }

  ModelClass chosen = options.model;
  ModelFit fit;
  if (options.model != ModelClass::Auto) {
    fit = fitModel(options.model, pts, source_size, target_size, options.condition);
  } else {
    // The ladder (DESIGN §2): the simplest model whose held-out error a richer one does not
    // beat by more than options.auto_improvement; an exactly determined richer model (no
    // held-out check possible) wins only where the validated ones do not fit exactly.
    struct Candidate {
      ModelClass model;
      ModelFit fit;
      double held_out;
      double train_rms;
    };
    std::vector<Candidate> candidates;
    std::string rejected;
    for (ModelClass model : kLadder) {
      ModelFit f = fitModel(model, pts, source_size, target_size, options.condition);
      if (!f.status) {
        if (static_cast<int>(used.size()) >= minimumMatches(model))
          rejected += std::string(rejected.empty() ? "" : "; ") + std::string(modelClassName(model)) +
                      " not determined";
        continue;
      }
      const double train = rms(reprojectionResiduals(f.camera, used));
      const double held = heldOutError(model, pts, source_size, target_size, options.condition);
      candidates.push_back({model, std::move(f), held, train});
    }
    if (candidates.empty()) {
      summary.status = fitModel(ModelClass::Translation, pts, source_size, target_size, true).status;
      if (summary.status) summary.status = Status::failure("no model could be fitted: " + rejected);
      return summary;
    }
    double best = std::numeric_limits<double>::infinity();
    for (const Candidate& c : candidates)
      if (!std::isnan(c.held_out)) best = std::min(best, std::max(c.held_out, kExactPx));
    const Candidate* pick = nullptr;
    for (const Candidate& c : candidates)
      if (!std::isnan(c.held_out) && std::max(c.held_out, kExactPx) * options.auto_improvement <= best) {
        pick = &c;
        break;
      }
    for (const Candidate& c : candidates) {
      const bool richer_exact = std::isnan(c.held_out) && c.train_rms <= kExactPx;
      if (richer_exact && (!pick || (c.model > pick->model && pick->train_rms > kExactPx))) pick = &c;
    }
    if (!pick) pick = &candidates.back();
    chosen = pick->model;
    fit = pick->fit;
    std::ostringstream why;
    why << "auto chose " << modelClassName(chosen) << "; held-out RMS:";
    for (const Candidate& c : candidates)
      why << " " << modelClassName(c.model) << " "
          << (std::isnan(c.held_out) ? std::string("n/a (exactly determined)") : fmt(c.held_out) + " px");
    if (!rejected.empty()) why << "; " << rejected;
    summary.record.reason = why.str();
  }
  if (!fit.status) {
    summary.status = fit.status;
    return summary;
  }
  summary.camera = fit.camera;
  summary.record.model = std::string(modelClassName(chosen));
  summary.record.matches = static_cast<int>(used.size());
  summary.record.residuals_px = reprojectionResiduals(fit.camera, used);
  summary.record.rms_px = rms(summary.record.residuals_px);
  summary.record.max_px = summary.record.residuals_px.empty()
                              ? 0.0
                              : *std::max_element(summary.record.residuals_px.begin(),
                                                  summary.record.residuals_px.end());
  for (Eigen::Index i = 0; i < std::min<Eigen::Index>(3, fit.singular_values.size()); ++i)
    summary.record.singular_values.push_back(fit.singular_values[i]);
  if (!fit.note.empty())
    summary.record.reason += (summary.record.reason.empty() ? "" : "; ") + fit.note;
  return summary;
}

}  // namespace artcam
