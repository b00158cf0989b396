// SPDX-License-Identifier: Apache-2.0
#include "core/fit/robust.h"

#include "core/model/frames.h"

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

// The matches in the normalised frames, once: scoring runs over every match for every sample,
// and the generic per-point camera evaluation (dynamic vectors) dominated the search.
struct NormalisedMatches {
  std::vector<Eigen::Vector3d> src;  // (u, v, 1)
  std::vector<Eigen::Vector2d> dst;
  double target_pixels_per_unit = 1.0;
};

NormalisedMatches normalise(const std::vector<PointMatch>& matches, FrameSize source_size,
                            FrameSize target_size) {
  NormalisedMatches n;
  n.target_pixels_per_unit = std::max(target_size.width, target_size.height) / 2.0;
  for (const PointMatch& m : matches) {
    const Eigen::Vector2d s = normalizedFromPixel(source_size, m.source.head<2>());
    n.src.emplace_back(s.x(), s.y(), 1.0);
    n.dst.push_back(normalizedFromPixel(target_size, m.target.head<2>()));
  }
  return n;
}

Scored score(const Camera& camera, const NormalisedMatches& matches, double threshold) {
  Scored s;
  s.cost = 0.0;
  const double t2 = threshold * threshold;
  const Eigen::Matrix3d q0 = camera.stages()[0].q[0], q1 = camera.stages()[0].q[1],
                        q2 = camera.stages()[0].q[2];
  const double scale2 = matches.target_pixels_per_unit * matches.target_pixels_per_unit;
  for (size_t k = 0; k < matches.src.size(); ++k) {
    const Eigen::Vector3d& x = matches.src[k];
    const double w = x.dot(q2 * x);
    const Eigen::Vector2d y(x.dot(q0 * x) / w, x.dot(q1 * x) / w);
    const double e2 = (y - matches.dst[k]).squaredNorm() * scale2;  // target pixels²
    const double capped = std::isfinite(e2) ? std::min(e2, t2) : t2;
    s.cost += capped;  // MSAC: inliers by their error, outliers by a constant
    if (std::isfinite(e2) && e2 < t2) s.inliers.push_back(static_cast<int>(k));
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

  const NormalisedMatches normalised = normalise(matches, source_size, target_size);
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
    Scored s = score(fit.camera, normalised, options.threshold_px);
    if (s.cost >= best.cost) continue;
    // Local optimisation: re-fit on the inliers while that keeps lowering the cost.
    for (int lo = 0; lo < 4 && static_cast<int>(s.inliers.size()) > sample_size; ++lo) {
      const FitSummary refit =
          fitImageCamera(pick(matches, s.inliers), source_size, target_size, exact);
      if (!refit.status) break;
      Scored t = score(refit.camera, normalised, options.threshold_px);
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
