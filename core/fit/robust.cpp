#include "core/fit/robust.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace artcam {
namespace {

struct Scored {
  double cost = std::numeric_limits<double>::infinity();
  std::vector<int> inliers;
};

Scored score(const Camera& camera, const std::vector<PointMatch>& matches, double threshold) {
  Scored s;
  s.cost = 0.0;
  const double t2 = threshold * threshold;
  const std::vector<double> e = reprojectionResiduals(camera, matches);
  for (size_t k = 0; k < e.size(); ++k) {
    const double e2 = std::isfinite(e[k]) ? e[k] * e[k] : t2;
    s.cost += std::min(e2, t2);  // MSAC: inliers by their error, outliers by a constant
    if (e2 < t2) s.inliers.push_back(static_cast<int>(k));
  }
  return s;
}

std::vector<PointMatch> pick(const std::vector<PointMatch>& matches, const std::vector<int>& idx) {
  std::vector<PointMatch> out;
  out.reserve(idx.size());
  for (int k : idx) out.push_back(matches[k]);
  return out;
}

}  // namespace

double ransacIterations(double confidence, double inlier_share, int sample_size, int max_iterations) {
  const double p_good = std::pow(inlier_share, sample_size);
  if (p_good >= 1.0) return 0.0;
  const double log_miss = std::log1p(-p_good);  // < 0 unless p_good underflows to 0
  if (!(log_miss < 0.0)) return max_iterations;
  return std::min<double>(max_iterations, std::log(1.0 - confidence) / log_miss);
}

RobustResult findInliers(const std::vector<PointMatch>& matches, FrameSize source_size,
                         FrameSize target_size, ModelClass model, const RobustOptions& options) {
  RobustResult result;
  const ModelClass sampled = model == ModelClass::Auto ? ModelClass::Quadratic : model;
  const int sample_size = minimumMatches(sampled, 2);
  const int m = static_cast<int>(matches.size());
  if (m < sample_size) {
    result.status = Status::failure("robust fitting of the " + std::string(modelClassName(sampled)) +
                                    " model needs at least " + std::to_string(sample_size) +
                                    " matches, have " + std::to_string(m));
    return result;
  }
  FitOptions exact;
  exact.model = sampled;
  exact.refine = false;
  exact.require_pole_free = false;
  exact.diagnostics = false;

  std::mt19937_64 rng(options.seed);
  std::vector<int> all(m);
  std::iota(all.begin(), all.end(), 0);
  Scored best;
  double needed = options.max_iterations;
  int it = 0;
  for (; it < options.max_iterations && it < needed; ++it) {
    // A random minimal set (partial Fisher–Yates).
    for (int k = 0; k < sample_size; ++k)
      std::swap(all[k], all[k + std::uniform_int_distribution<int>(0, m - 1 - k)(rng)]);
    const FitSummary fit = fitImageCamera(
        pick(matches, std::vector<int>(all.begin(), all.begin() + sample_size)), source_size,
        target_size, exact);
    if (!fit.status) continue;
    Scored s = score(fit.camera, matches, options.threshold_px);
    if (s.cost >= best.cost) continue;
    // Local optimisation: re-fit on the inliers while that keeps lowering the cost.
    for (int lo = 0; lo < 4 && static_cast<int>(s.inliers.size()) > sample_size; ++lo) {
      const FitSummary refit =
          fitImageCamera(pick(matches, s.inliers), source_size, target_size, exact);
      if (!refit.status) break;
      Scored t = score(refit.camera, matches, options.threshold_px);
      if (t.cost >= s.cost) break;
      s = std::move(t);
    }
    best = std::move(s);
    needed = ransacIterations(options.confidence, static_cast<double>(best.inliers.size()) / m,
                              sample_size, options.max_iterations);
  }
  result.iterations = it;
  if (static_cast<int>(best.inliers.size()) < sample_size) {
    result.status = Status::failure("no " + std::string(modelClassName(sampled)) +
                                    " explains more than " + std::to_string(best.inliers.size()) +
                                    " of the " + std::to_string(m) + " matches within " +
                                    std::to_string(options.threshold_px) + " px");
    return result;
  }
  result.inliers = std::move(best.inliers);
  return result;
}

}  // namespace artcam
