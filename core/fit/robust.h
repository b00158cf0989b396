// SPDX-License-Identifier: Apache-2.0
// Robust fitting: MSAC over minimal sets with local optimisation (LO-RANSAC, msac.h). Hand-
// clicked pairs include a wrong click now and then; detector matches include many. Each
// iteration fits the model exactly to a random minimal set (9 pairs for the quadratic), scores
// every match by min(e², t²) (MSAC), and when a better model appears re-fits it on its inliers
// (the local optimisation that makes minimal-set noise matter less). Iterations adapt to the
// inlier ratio for the requested confidence.
#pragma once

#include "core/fit/fit_image.h"
#include "core/fit/msac.h"

#include <vector>

namespace artcam {

struct RobustOptions {
  double threshold_px = 3.0;  // inlier if the reprojection error is below this
  MsacOptions search;         // confidence, iterations, the fixed seed (same input, same inliers)
};

struct RobustResult {
  Status status;
  std::vector<int> inliers;  // indices into the matches given
  int iterations = 0;
};

// `model` is the class sampled (Auto samples the quadratic). Matches must all be enabled.
RobustResult findInliers(const std::vector<PointMatch>& matches, FrameSize source_size,
                         FrameSize target_size, ModelClass model, const RobustOptions& options);

}  // namespace artcam
