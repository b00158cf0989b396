// SPDX-License-Identifier: Apache-2.0
// Plain data shared by fitting, files and the GUI: point matches and the report of a fit.
// Positions are in PIXELS of the source and target frames for image cameras (centres at
// i + 0.5), object units for 3D; colours are linear RGB in [0, 1].
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

// The largest magnitude a match coordinate (or colour) may have: no photo, frame or colour
// comes near 1e9, and beyond it the fit's residuals and records overflow or lose every digit
// that matters. Every reader of matches (CSV, project, lines) refuses a larger value where it
// can name the row or the JSON path.
inline constexpr double kMaxMatchValue = 1e9;

struct PointMatch {
  Eigen::VectorXd source;  // 2 (image), 3 (object or colour) coordinates, not homogeneous
  Eigen::VectorXd target;
  bool enabled = true;
};

// One rung of the model ladder as the fit saw it, so a reader can check the choice.
struct ModelScore {
  std::string model;
  double rms_px = -1.0;           // residual on all enabled matches; -1: the model did not fit
  double held_out_rms_px = -1.0;  // K-fold / leave-one-out; -1: not computable
  double criterion = -1.0;        // the value the choice compared (FitRecord::criterion); -1: none
  std::string note;               // why it was not eligible, empty when it was
};

struct FitRecord {
  std::string model;                 // "translation", "similarity", "affine", "homography", "quadratic"
  int matches = 0;                   // enabled matches used
  double rms_px = 0.0;               // reprojection residual in target pixels
  double max_px = 0.0;
  std::vector<double> residuals_px;  // one per enabled match, in match order
  std::vector<double> singular_values;  // the smallest few of the design matrix, ascending
  std::string reason;                // why this model (auto), one line
  double held_out_rms_px = -1.0;     // K-fold (leave-one-out up to 10 matches); -1: not computable
  double algebraic_rms_px = -1.0;    // before refinement; -1: not refined
  bool pole_checked = false;         // the pole check applies (single-stage 2D cameras)
  bool pole_free = true;             // the denominator keeps one sign over the source frame
  double pole_margin = 1.0;          // min |denominator| / max |denominator| over the frame
  std::vector<int> inliers;          // robust fits: indices (into the enabled matches) kept
  // The ladder as scored (auto, and named models with diagnostics), simplest first, and what
  // the scores are: "aic" (information criterion, px²-scaled) or "held-out" (RMS px).
  std::vector<ModelScore> models;
  std::string criterion;
};

}  // namespace artcam
