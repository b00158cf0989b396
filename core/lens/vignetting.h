// SPDX-License-Identifier: Apache-2.0
// Vignetting as part of the camera: a radial gain on colour, the position→colour coupling of
// eq 6/7 (the paper's Q_pc) carried as a chain so it can have the degree a lens needs.
//
// The gain. g(t) = (n0 + n1 t + n2 t²) / (1 + d1 t + d2 t²), with t = |p − c|² / R² for a
// source pixel p, the vignetting centre c and R half the frame's diagonal (so t ≤ 1 over a
// centred frame). lensfun's model is the polynomial 1 + k1 t + k2 t² + k3 t³ (`pa`, for
// simulating) and its inverse (for correcting); a ratio of quadratics in t follows both within
// a fraction of a percent where a ratio of linear functions of t is off by up to 13 %
// (lensfun's Canon EF 50 mm f/1.8 polynomial at f/2 over t in [0, 1]).
//
// The camera. A colour output is at most bilinear in colour and position, so the gain is the
// shading block's (camera.h), in three stages over [position | colour | shading]:
//   1. the camera's own first stage, and shading ← (t, 1) from the source position;
//   2. the camera's later stages, if any, and shading ← (N(s), D(s)), so s = g(t);
//   3. colour (a·r, a·g, a·b) ← s·(a·r, a·g, a·b), alpha kept; everything else passed on.
// The gain reads the SOURCE position: the photo as shot when correcting (lensfun corrects the
// colour of the photo before its geometry), the clean picture when simulating (the samples then
// give the gain lensfun applies at the target, fitted as a function of the source point).
//
// The fit. The centre comes from the samples (Gauss–Newton on a cubic in t, started at the
// frame's centre; it stays there when the gain is flat), then the ratio by linearised least
// squares on the relative error, reweighted by the denominator (Sanathanan–Koerner), on t
// already normalised to [0, 1]. A denominator with a zero over the frame's range of t is
// refused in favour of the quadratic polynomial (d1 = d2 = 0), which has none. The figures are
// the relative error g_fit / g − 1 over the check samples, in percent.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/status.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

struct RadialGain {
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  double radius_px = 1.0;                                 // R
  Eigen::Vector3d numerator{1.0, 0.0, 0.0};               // n0, n1, n2
  Eigen::Vector2d denominator = Eigen::Vector2d::Zero();  // d1, d2 (d0 = 1)

  double t(const Eigen::Vector2d& source_px) const {
    return (source_px - centre_px).squaredNorm() / (radius_px * radius_px);
  }
  double operator()(const Eigen::Vector2d& source_px) const;
};

struct GainSample {
  Eigen::Vector2d source_px;
  double gain = 1.0;
};

struct GainFitSummary {
  Status status;  // not ok: too few samples, a gain that is not positive and finite
  RadialGain gain;
  bool rational = true;      // false: the quadratic polynomial was kept (the ratio had a pole)
  double rms_percent = 0.0;  // relative error over the check samples
  double max_percent = 0.0;
  int checked = 0;
  // "gain 0.43–1.00 over the frame, max 0.12 %, RMS 0.03 % over 38 000 points"
  std::string report() const;
};

// Fits g to `fit` and measures it on `check` (both source pixels of `frame`).
GainFitSummary fitRadialGain(const std::vector<GainSample>& fit,
                             const std::vector<GainSample>& check, FrameSize frame);

// `camera` (blocks [position 3] or [position 3 | colour 4], one or more stages) with the gain
// applied to its colour at the source point, as the three-stage chain above. Throws
// std::invalid_argument for other block layouts.
Camera withRadialGain(const Camera& camera, const RadialGain& gain);

// Whether `camera` carries a gain (it has a shading block, as withRadialGain makes).
bool hasShading(const Camera& camera);

// A flat-field photo (a grey card or a white wall shot through the lens, linear light) to the
// camera that corrects its vignetting: the gain that makes the field flat at its centre's
// level. The photo is averaged over cells of `cell_px` (noise and texture fall away), the
// brightest centre cell is the reference; cells whose level is not positive are refused.
struct FlatFieldOptions {
  int cells = 48;                  // cells along the longer side (the fit's samples)
  double max_error_percent = 1.0;  // within: the fit is kept; beyond: said (not refused)
};
struct FlatFieldSummary {
  GainFitSummary fit;
  double darkest = 1.0;  // the darkest cell over the reference: how much the lens vignettes
  Camera camera;         // identity geometry of the photo's size, the correcting gain
};
FlatFieldSummary fitFlatField(const ImageF& flat, const FlatFieldOptions& options = {});

}  // namespace artcam
