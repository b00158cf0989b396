// SPDX-License-Identifier: Apache-2.0
// Fitting an image camera (2D position block, n = 3) to point matches: the paper's §4 DLT
// with conditioning on both sides, and the model ladder.
//
// Matches are in PIXELS of their frames (centres at i + 0.5). They are first taken to the
// normalised frames of frames.h, then conditioned (centroid to the origin, RMS distance √2)
// before the design matrix is built; the result is returned in the normalised frames, the way
// cameras are stored.
#pragma once

#include "core/fit/options_check.h"
#include "core/model/camera.h"
#include "core/model/fit_record.h"
#include "core/model/status.h"

#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class ModelClass { Auto, Translation, Similarity, Affine, Homography, Quadratic };

std::string_view modelClassName(ModelClass model);
std::optional<ModelClass> modelClassFromName(std::string_view name);
// Fewest matches that determine the class: 2D (dimension 2) translation 1 … quadratic 9;
// object space (dimension 3) translation 1, affine 4, homography 5, quadratic 13 (40 unknowns
// up to scale, 3 equations per match; the paper's formula rounds it up to 14).
int minimumMatches(ModelClass model, int dimension = 2);

struct FitOptions {
  ModelClass model = ModelClass::Auto;
  // Skip the conditioning step (for the raw-DLT benchmark only).
  bool condition = true;
  // Auto with many matches (every model's held-out error trusted): a richer model must lower
  // the held-out error by this factor to be chosen, so auto stays within 2 % of the best.
  double auto_improvement = 0.98;
  // Auto with few matches: the noise level of the information criterion, a click's precision
  // in target pixels (fit_image.cpp, chooseModel).
  double click_sigma_px = 1.0;
  // Levenberg–Marquardt on the reprojection error after the DLT (quadratic models; refine.h),
  // then a few seeded restarts near the result in case LM stopped in a local minimum (kept only
  // when better on all matches and pole-free; fit_image.cpp, restartNearby).
  bool refine = true;
  // Nearby restarts after LM (with refine; 0: none). Held-out folds never restart: the
  // cross-validation compares model classes, the restarts polish the camera returned.
  int restarts = 8;
  // Image cameras: refuse a camera whose denominator vanishes inside the source frame; for
  // the quadratic, first retry from the lifted homography and affine fits (poles.h).
  bool require_pole_free = true;
  // Held-out (cross-validated) error of a named model, for the report. Off inside RANSAC.
  bool diagnostics = true;
  // MSAC/LO-RANSAC over minimal sets first, then the fit on the inliers (robust.h).
  bool robust = false;
  double robust_threshold_px = 3.0;

  // The ranges (options_check.h): model one of the classes, auto_improvement in (0, 1],
  // click_sigma_px and robust_threshold_px finite and above 0, restarts 0..1000. ok, or a
  // failure naming the first field outside its range; fitImageCamera and fitObjectCamera return
  // that failure without fitting.
  Status check(const FieldNames& names = {}) const;
};

struct FitSummary {
  Status status;      // not ok: no camera; message names the cause and how to fix it
  Camera camera;      // valid when status.ok
  FitRecord record;   // residuals, RMS, max, singular values, reason
  std::string report() const;  // one line for the CLI and the status bar
};

FitSummary fitImageCamera(const std::vector<PointMatch>& matches, FrameSize source_size,
                          FrameSize target_size, const FitOptions& options = {});

// Object-space cameras (position block (X, Y, Z, 1), n = 4) from 3D matches, in object units;
// no frames. The ladder is translation, affine, homography (4×4 projective), quadratic.
FitSummary fitObjectCamera(const std::vector<PointMatch>& matches, const FitOptions& options = {});

// Residuals (target pixels) of a camera on matches, in match order; infinity where unmapped.
std::vector<double> reprojectionResiduals(const Camera& camera,
                                          const std::vector<PointMatch>& matches);

}  // namespace artcam
