// SPDX-License-Identifier: Apache-2.0
// Robust fitting: MSAC over minimal sets with local optimisation (LO-RANSAC). Hand-
// clicked pairs include a wrong click now and then; detector matches include many. Each
// iteration fits the model exactly to a random minimal set (9 pairs for the quadratic), scores
// every match by min(e², t²) (MSAC), and when a better model appears re-fits it on its inliers
// (the local optimisation that makes minimal-set noise matter less). Iterations adapt to the
// inlier ratio for the requested confidence.
#pragma once

#include "core/fit/fit_image.h"

#include <cstdint>
#include <vector>

namespace artcam {

struct RobustOptions {
  double threshold_px = 3.0;   // inlier if the reprojection error is below this
  double confidence = 0.999;   // that at least one all-inlier minimal set was drawn
  int max_iterations = 10000;
  std::uint64_t seed = 20261122;  // fixed: the same input gives the same inliers
};

struct RobustResult {
  Status status;
  std::vector<int> inliers;  // indices into the matches given
  int iterations = 0;
};

// Iterations that draw at least one all-inlier minimal set with probability `confidence`:
// log(1 - confidence) / log(1 - w^k). Computed with log1p: for a small inlier share w^k falls
// below 1e-16, 1 - w^k rounds to 1 and the plain formula gives -inf, which once stopped the
// search after a single draw. Capped at max_iterations.
double ransacIterations(double confidence, double inlier_share, int sample_size, int max_iterations);

// `model` is the class sampled (Auto samples the quadratic). Matches must all be enabled.
RobustResult findInliers(const std::vector<PointMatch>& matches, FrameSize source_size,
                         FrameSize target_size, ModelClass model, const RobustOptions& options);

}  // namespace artcam
