// SPDX-License-Identifier: Apache-2.0
// Aerial perspective (the paper's §3): contrast falls with the logarithm of distance, towards
// a haze colour. Built as a two-stage chain over [position 3 | colour 4 | depth 2]
// (a chain keeps each stage one quadratic form, so each stays linear to fit):
//
//   stage 1, depth only:  l = (d Q_d dᵀ) / (d Q_h dᵀ) for d = (depth, 1), a rational quadratic
//            fitted to the normalised log  l*(d) = ln(d/near) / ln(far/near)  over [near, far]
//            ("we fitted an ARTcam to approximate a logarithmic function", §3);
//   stage 2, depth × colour (the cd coupling of eq 7's partition):
//            c' = c·(1 − t·l) + t·l·a·haze   (premultiplied; alpha a unchanged),
//            each output a quadratic form in [c | l, 1]; t is the strength.
// Position passes unchanged (identity geometry: the colour-only path of attributed.h); the
// depth output is l, the log-like depth.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

namespace artcam {

struct AerialParams {
  Eigen::Vector3d haze = {0.62, 0.72, 0.86};  // linear RGB the far distance fades to
  double strength = 0.7;                       // t: the fraction of haze at `far`
  double near = 1.0;                           // depth where haze starts (l = 0)
  double far = 100.0;                          // depth where l = 1
};

// The stage-1 fit: 2×2 tensors on (d, 1) for numerator and denominator.
struct LogDepthFit {
  Eigen::Matrix2d numerator = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d denominator = Eigen::Matrix2d::Zero();
  double max_error = 0.0;  // max |l − l*| over [near, far] (dense samples), units of l
  double rms_error = 0.0;
};
// Least-squares rational fit (linearised, then re-weighted by the denominator, Sanathanan–
// Koerner) in a normalised depth variable; throws std::invalid_argument unless
// 0 < near < far, or if the fitted denominator changes sign on [near, far].
LogDepthFit fitLogDepth(double near, double far, int samples = 256);
// The closed form the fit approximates.
double normalisedLogDepth(double depth, double near, double far);

Camera aerialPerspectiveCamera(const AerialParams& p, FrameSize source, FrameSize target,
                               LogDepthFit* fit = nullptr);

}  // namespace artcam
