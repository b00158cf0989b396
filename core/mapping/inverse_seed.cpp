// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/inverse_seed.h"

#include "core/fit/fit_image.h"
#include "core/mapping/inverse.h"

#include <Eigen/LU>

#include <algorithm>
#include <string>
#include <vector>

namespace artcam {

Result<RationalMap> fitInverseSeed(const RationalMap& forward, FrameSize source_px,
                                   FrameSize target_px, const InverseSeedOptions& options) {
  const auto centre = centreReference(forward, source_px);
  if (!centre) return Result<RationalMap>::failure("the map is undefined at the source centre");
  const int g = std::max(4, options.grid);
  // Targets far outside the output frame would dominate a fit that only needs to be good on it.
  const double reach = 2.0 * std::max(target_px.width, target_px.height);
  std::vector<PointMatch> matches;
  matches.reserve(static_cast<size_t>(g) * static_cast<size_t>(g));
  for (int j = 0; j < g; ++j) {
    for (int i = 0; i < g; ++i) {
      const Eigen::Vector2d s((i + 0.5) * source_px.width / g, (j + 0.5) * source_px.height / g);
      Eigen::Vector2d t;
      Eigen::Matrix2d jac;
      unsigned signs = 0;
      if (!forward.evaluate(s, t, &jac, &signs)) continue;
      // Only the sheet the renderer keeps: the centre's side of every pole curve, no fold.
      if (signs != centre->denominator_signs) continue;
      if ((jac.determinant() > 0.0) != centre->det_positive) continue;
      if ((t - Eigen::Vector2d(target_px.width / 2.0, target_px.height / 2.0)).norm() > reach)
        continue;
      PointMatch m;
      m.source = t;  // roles swapped: the camera we fit maps output pixels to source pixels
      m.target = s;
      matches.push_back(std::move(m));
    }
  }
  FitOptions fo;
  fo.model = ModelClass::Quadratic;
  // A seed for Newton, fitted at every render: no held-out diagnostics (refits per fold) and
  // no nearby restarts (more LM runs): the DLT + one LM, a fraction of the full fit's time
  // with the same certified share and error (the correction grid and the per-pixel check
  // absorb what is left).
  fo.diagnostics = false;
  fo.restarts = 0;
  const FitSummary fit = fitImageCamera(matches, target_px, source_px, fo);
  if (!fit.status) return Result<RationalMap>::failure(fit.status.message);
  try {
    return Result<RationalMap>::success(RationalMap(fit.camera, target_px, source_px));
  } catch (const std::invalid_argument& e) {
    return Result<RationalMap>::failure(e.what());
  }
}

}  // namespace artcam
