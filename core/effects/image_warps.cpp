// SPDX-License-Identifier: Apache-2.0
#include "core/effects/image_warps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {

namespace {

// Half extents of the frame in normalised units.
Eigen::Vector2d halfExtent(FrameSize f) {
  const double s = std::max(f.width, f.height) / 2.0;
  return {f.width / 2.0 / s, f.height / 2.0 / s};
}

Eigen::Vector3d e(int i) { return Eigen::Vector3d::Unit(i); }

Camera rtcamOf(const Eigen::MatrixXd& qu, const Eigen::MatrixXd& qv, const Eigen::MatrixXd& qw,
               FrameSize frame) {
  Stage stage{{qu, qv, qw}};
  return Camera({Block{BlockKind::Position, 3}}, {stage}, frame, frame);
}

}  // namespace

Camera radialLensCamera(double k, FrameSize frame) {
  const double corner2 = halfExtent(frame).squaredNorm();
  if (!std::isfinite(k) || k * corner2 >= 0.95)
    throw std::invalid_argument("radial lens: k = " + std::to_string(k) +
                                " puts the pole circle inside the frame (need k·r_corner² < 0.95)");
  Eigen::Matrix3d w = symmetricOuter(e(2), e(2));
  w(0, 0) = w(1, 1) = -k;  // w² − k(u² + v²)
  return rtcamOf(symmetricOuter(e(0), e(2)), symmetricOuter(e(1), e(2)), w, frame);
}

Camera lensDistortionCamera(const LensDistortion& lens, FrameSize frame) {
  const Eigen::Vector2d c = lens.centre;
  if (!std::isfinite(lens.k1) || !std::isfinite(lens.k2) || !c.allFinite() ||
      !std::isfinite(lens.scale) || lens.scale <= 0.0)
    throw std::invalid_argument("lens distortion: k1, k2, centre and a positive scale, finite");
  // The largest |q| over the frame is at a corner.
  const Eigen::Vector2d h = halfExtent(frame);
  double r0 = 0.0;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      r0 = std::max(r0, (Eigen::Vector2d(sx * h.x(), sy * h.y()) - c).norm());
  if (lens.k1 * r0 * r0 >= 0.95)
    throw std::invalid_argument("lens distortion: k1 = " + std::to_string(lens.k1) +
                                " puts the first pole circle inside the frame (need k1·r² < 0.95 "
                                "at the farthest corner from the centre)");
  // |q₁| = r/(1 − k1 r²) over r ≤ r0: increasing for k1 ≥ 0; for k1 < 0 largest at
  // r = 1/√−k1 (value 1/(2√−k1)) when that is inside.
  double r1 = r0 / (1.0 - lens.k1 * r0 * r0);
  if (lens.k1 < 0.0 && 1.0 / std::sqrt(-lens.k1) < r0) r1 = 0.5 / std::sqrt(-lens.k1);
  if (lens.k2 * r1 * r1 >= 0.95)
    throw std::invalid_argument("lens distortion: k2 = " + std::to_string(lens.k2) +
                                " puts the second pole circle inside the first stage's picture "
                                "(need k2·r₁² < 0.95)");
  // q's components as linear forms of (u, v, w), and |q|² as a quadratic form.
  const Eigen::Vector3d qu = e(0) - c.x() * e(2), qv = e(1) - c.y() * e(2);
  const Eigen::Matrix3d q2 = qu * qu.transpose() + qv * qv.transpose();
  const auto stage = [&](double k, double s) {
    const Eigen::Matrix3d den = symmetricOuter(e(2), e(2)) - k * q2;  // w² − k|q|²
    // c + s·q/(1 − k|q|²) over the common denominator: s·q·w + c·(w² − k|q|²).
    return Stage{{s * symmetricOuter(qu, e(2)) + c.x() * den,
                  s * symmetricOuter(qv, e(2)) + c.y() * den, den}};
  };
  std::vector<Stage> stages;
  if (lens.k2 == 0.0) {
    stages = {stage(lens.k1, lens.scale)};
  } else {
    stages = {stage(lens.k1, 1.0), stage(lens.k2, lens.scale)};
  }
  return Camera({Block{BlockKind::Position, 3}}, std::move(stages), frame, frame);
}

Camera twistCamera(double rate, FrameSize frame) {
  if (!std::isfinite(rate)) throw std::invalid_argument("twist: rate must be finite");
  return rtcamOf(symmetricOuter(e(0), e(2)),
                 symmetricOuter(e(1), e(2)) + rate * symmetricOuter(e(0), e(1)),
                 symmetricOuter(e(2), e(2)), frame);
}

Camera inversePerspectiveCamera(double gain, FrameSize frame) {
  const double half_v = halfExtent(frame).y();
  if (!std::isfinite(gain) || std::abs(gain) * half_v >= 0.9)
    throw std::invalid_argument("inverse perspective: gain " + std::to_string(gain) +
                                " puts the pole line v = -1/gain inside the frame");
  const Eigen::Vector3d den = e(2) + gain * e(1);
  return rtcamOf(symmetricOuter(e(0), e(2)), symmetricOuter(e(1), e(2)),
                 symmetricOuter(den, e(2)), frame);
}

}  // namespace artcam
