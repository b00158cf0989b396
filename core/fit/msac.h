// SPDX-License-Identifier: Apache-2.0
// MSAC with local optimisation (LO-RANSAC), generic over what is fitted: the geometry fit's
// robust option (robust.h) and the colour fit's (fit_colour.h) run this one search. Each
// iteration draws a random minimal set (a partial Fisher–Yates shuffle from a seeded
// mt19937_64, so the same input gives the same inliers), fits it and scores the model over
// every item by Σ min(e², t²) (MSAC: inliers by their error, outliers by a constant). A model
// better than the best so far is re-fitted on its inliers while that lowers the cost (at most
// four rounds: the local optimisation that makes minimal-set noise matter less), and the
// iterations still needed follow the best inlier share for the requested confidence.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace artcam {

// A model's score over every item.
struct MsacScore {
  double cost = 0.0;         // Σ min(e², t²)
  std::vector<int> inliers;  // the items with e < t, in item order
  // Adds one item's squared error; a non-finite one (an item the model does not map) is an
  // outlier, costing t².
  void add(int item, double squared_error, double threshold_squared);
};

struct MsacOptions {
  double confidence = 0.999;  // that at least one all-inlier minimal set was drawn
  int max_iterations = 10000;
  std::uint64_t seed = 20261122;
};

struct MsacProblem {
  int items = 0;
  int sample_size = 0;  // the minimal set; at most `items`
  // Fits a model to the minimal set `sample` and scores it over every item; nullopt when the
  // set determines no model.
  std::function<std::optional<MsacScore>(const std::vector<int>& sample)> fit_sample;
  // The local optimisation: a model fitted to `inliers` (more than a minimal set), scored over
  // every item; nullopt when none fits them.
  std::function<std::optional<MsacScore>(const std::vector<int>& inliers)> refit;
};

struct MsacResult {
  std::vector<int> inliers;  // the best model's; empty when no minimal set fitted
  int iterations = 0;
};

// Iterations that draw at least one all-inlier minimal set with probability `confidence`:
// log(1 - confidence) / log(1 - w^k). Computed with log1p: for a small inlier share w^k falls
// below 1e-16, 1 - w^k rounds to 1 and the plain formula gives -inf, which once stopped the
// search after a single draw. Capped at max_iterations.
double ransacIterations(double confidence, double inlier_share, int sample_size,
                        int max_iterations);

MsacResult runMsac(const MsacProblem& problem, const MsacOptions& options);

}  // namespace artcam
