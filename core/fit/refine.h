// SPDX-License-Identifier: Apache-2.0
// Levenberg–Marquardt refinement of an image camera's reprojection error: the
// algebraic DLT minimises |D r|, which weighs matches by their denominators; the geometric
// error is what a user sees. Works in the normalised frames on the 18 upper-triangle entries
// of Q_1..Q_3 (scale is a gauge freedom: the damping handles it and steps are renormalised).
//
// Guarantees: the result is never worse than the start (only cost-reducing steps are taken)
// and, when the start is pole-free over the source frame, so is the result (a step that puts
// a pole in the frame, or comes within min_pole_margin of one, is rejected like one that
// raises the cost).
#pragma once

#include "core/fit/normalize.h"
#include "core/model/camera.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

struct RefineOptions {
  int max_iterations = 100;
  double relative_tolerance = 1e-10;  // stop when the cost falls by less than this fraction
  bool keep_pole_free = true;
  // With keep_pole_free, a step is also refused when it brings the denominator closer to zero
  // than this margin (min |D| / max |D| over the frame, poles.h), or than the start's margin if
  // that is lower. Without it, 9 noisy matches (one redundant equation) let LM fit them to
  // 0.03 px by parking the pole curve on a frame corner (margin ~1e-11): pole-free by the sign
  // test, yet the map runs to 1e10 px there. 1e-3 keeps |D| within a factor 1000 over the frame.
  double min_pole_margin = 1e-3;
  // The source frame in normalised coordinates (for the pole check).
  Eigen::Vector2d frame_lo = Eigen::Vector2d(-1, -1);
  Eigen::Vector2d frame_hi = Eigen::Vector2d(1, 1);
};

struct RefineSummary {
  double initial_rms = 0.0;  // normalised target units
  double final_rms = 0.0;
  int iterations = 0;
  // Steps that lowered the cost but were refused because they put a pole in the frame: the
  // result may sit against the pole constraint rather than at a minimum.
  int pole_rejections = 0;
  std::string stop_reason;
};

// src/dst: matched points (2 × m) in the normalised source and target frames.
Camera refineReprojection(const Camera& start, const Points& src, const Points& dst,
                          const RefineOptions& options, RefineSummary* summary = nullptr);

}  // namespace artcam
