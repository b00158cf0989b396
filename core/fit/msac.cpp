// SPDX-License-Identifier: Apache-2.0
#include "core/fit/msac.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <utility>

namespace artcam {

void MsacScore::add(int item, double squared_error, double threshold_squared) {
  const bool finite = std::isfinite(squared_error);
  cost += finite ? std::min(squared_error, threshold_squared) : threshold_squared;
  if (finite && squared_error < threshold_squared) inliers.push_back(item);
}

double ransacIterations(double confidence, double inlier_share, int sample_size,
                        int max_iterations) {
  const double p_good = std::pow(inlier_share, sample_size);
  if (p_good >= 1.0) return 0.0;
  const double log_miss = std::log1p(-p_good);  // < 0 unless p_good underflows to 0
  if (!(log_miss < 0.0)) return max_iterations;
  return std::min<double>(max_iterations, std::log(1.0 - confidence) / log_miss);
}

MsacResult runMsac(const MsacProblem& problem, const MsacOptions& options) {
  const int m = problem.items, k = problem.sample_size;
  MsacResult result;
  std::mt19937_64 rng(options.seed);
  std::vector<int> all(static_cast<size_t>(m));
  std::iota(all.begin(), all.end(), 0);
  MsacScore best;
  best.cost = std::numeric_limits<double>::infinity();
  double needed = options.max_iterations;
  int it = 0;
  for (; it < options.max_iterations && it < needed; ++it) {
    for (int j = 0; j < k; ++j)
      std::swap(all[j], all[j + std::uniform_int_distribution<int>(0, m - 1 - j)(rng)]);
    std::optional<MsacScore> s = problem.fit_sample(std::vector<int>(all.begin(), all.begin() + k));
    if (!s || s->cost >= best.cost) continue;
    for (int lo = 0; lo < 4 && static_cast<int>(s->inliers.size()) > k; ++lo) {
      std::optional<MsacScore> t = problem.refit(s->inliers);
      if (!t || t->cost >= s->cost) break;
      s = std::move(t);
    }
    best = std::move(*s);
    needed = ransacIterations(options.confidence, static_cast<double>(best.inliers.size()) / m, k,
                              options.max_iterations);
  }
  result.iterations = it;
  result.inliers = std::move(best.inliers);
  return result;
}

}  // namespace artcam
