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
