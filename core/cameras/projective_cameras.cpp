// SPDX-License-Identifier: Apache-2.0
#include "core/cameras/projective_cameras.h"

#include <cmath>
#include <stdexcept>

namespace artcam {

using tensor4::linear;
using tensor4::product;
using tensor4::W;
using tensor4::X;
using tensor4::Y;
using tensor4::Z;

namespace {

Ray worldRay(const CameraPose& pose, const Eigen::Vector3d& origin_cam,
             const Eigen::Vector3d& direction_cam) {
  return {pose.worldFromCamera(origin_cam), pose.rotation.transpose() * direction_cam};
}

void requirePositive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument(std::string(what) + " must be positive");
}

}  // namespace

Camera pinholeCamera(const PinholeParams& p) {
  requirePositive(p.focal, "pinhole focal");
  const double f = p.focal;
  return objectCamera(
      {product(linear(f, 0, p.principal.x(), 0), W()),
       product(linear(0, f, p.principal.y(), 0), W()), product(W(), W()), product(Z(), W())},
      p.pose);
}

Ray pinholeRay(const PinholeParams& p, const Eigen::Vector2d& image) {
  const Eigen::Vector2d xy = (image - p.principal) / p.focal;
  return worldRay(p.pose, Eigen::Vector3d::Zero(), Eigen::Vector3d(xy.x(), xy.y(), 1.0));
}

Camera orthographicCamera(const OrthographicParams& p) {
  requirePositive(p.scale, "orthographic scale");
  requirePositive(p.far, "orthographic far");
  const double s = p.scale;
  return objectCamera({product(s * X(), W()), product(s * Y(), W()),
                       product(linear(0, 0, -1.0 / p.far, 1), W()), product(W(), W())},
                      p.pose);
}

Ray orthographicRay(const OrthographicParams& p, const Eigen::Vector2d& image) {
  return worldRay(p.pose, Eigen::Vector3d(image.x() / p.scale, image.y() / p.scale, 0),
                  Eigen::Vector3d::UnitZ());
}

Camera pushbroomCamera(const PushbroomParams& p) {
  requirePositive(p.focal, "push-broom focal");
  requirePositive(p.scale, "push-broom scale");
  return objectCamera({product(p.scale * X(), Z()), product(p.focal * Y(), W()), product(W(), W()),
                       product(Z(), W())},
                      p.pose);
}

Ray pushbroomRay(const PushbroomParams& p, const Eigen::Vector2d& image) {
  // The sensor at sweep position X = u/s sees the fan of directions (0, v/f, 1).
  return worldRay(p.pose, Eigen::Vector3d(image.x() / p.scale, 0, 0),
                  Eigen::Vector3d(0, image.y() / p.focal, 1));
}

Camera xslitCamera(const XSlitParams& p) {
  requirePositive(p.focal, "crossed-slits focal");
  if (p.slit_u_depth == p.slit_v_depth)
    throw std::invalid_argument("crossed slits at the same depth intersect: that is a pinhole");
  const Eigen::Vector4d za = linear(0, 0, 1, -p.slit_u_depth);  // Z - aW
  const Eigen::Vector4d zb = linear(0, 0, 1, -p.slit_v_depth);  // Z - bW
  // u = fX/(Z-a) = fX(Z-b)/((Z-a)(Z-b)), and v likewise: one shared quadratic denominator.
  return objectCamera(
      {product(p.focal * X(), zb), product(p.focal * Y(), za), product(W(), W()), product(za, zb)},
      p.pose);
}

Ray xslitRay(const XSlitParams& p, const Eigen::Vector2d& image) {
  // At depth t the ray is at (u(t - a)/f, v(t - b)/f, t): it meets {X=0, Z=a} and {Y=0, Z=b}.
  const double a = p.slit_u_depth, b = p.slit_v_depth, f = p.focal;
  return worldRay(p.pose, Eigen::Vector3d(-image.x() * a / f, -image.y() * b / f, 0),
                  Eigen::Vector3d(image.x() / f, image.y() / f, 1));
}

Camera rationalLensCamera(const Eigen::Matrix<double, 3, 6>& a, const CameraPose& pose) {
  if (!a.allFinite()) throw std::invalid_argument("rational lens matrix has a non-finite entry");
  // χ = (X², XY, Y², XZ, YZ, Z²); cross terms are split over the two symmetric entries.
  const auto form = [&](int row) {
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(4, 4);
    q(0, 0) = a(row, 0);
    q(0, 1) = q(1, 0) = 0.5 * a(row, 1);
    q(1, 1) = a(row, 2);
    q(0, 2) = q(2, 0) = 0.5 * a(row, 3);
    q(1, 2) = q(2, 1) = 0.5 * a(row, 4);
    q(2, 2) = a(row, 5);
    return q;
  };
  return objectCamera({form(0), form(1), product(Z(), W()), form(2)}, pose);
}

Eigen::Matrix<double, 3, 6> rationalLensMatrix(const RationalLensParams& p) {
  requirePositive(p.focal, "rational lens focal");
  Eigen::Matrix<double, 3, 6> a = Eigen::Matrix<double, 3, 6>::Zero();
  a(0, 3) = p.focal;  // f·XZ
  a(1, 4) = p.focal;  // f·YZ
  a(2, 0) = p.k;      // Z² + k(X² + Y²)
  a(2, 2) = p.k;
  a(2, 5) = 1.0;
  return a;
}

Camera rationalLensCamera(const RationalLensParams& p) {
  return rationalLensCamera(rationalLensMatrix(p), p.pose);
}

std::optional<Ray> rationalLensRay(const RationalLensParams& p, const Eigen::Vector2d& image) {
  // Image radius r = ρ/(1 + kρ²) for the undistorted radius ρ = |x|; the root that tends to r
  // as k → 0, in the form without cancellation: ρ = 2r / (1 + √(1 - 4kr²)).
  const Eigen::Vector2d distorted = image / p.focal;
  const double r = distorted.norm();
  const double disc = 1.0 - 4.0 * p.k * r * r;
  if (disc < 0) return std::nullopt;
  const double rho = 2.0 * r / (1.0 + std::sqrt(disc));
  const Eigen::Vector2d x = distorted * (1.0 + p.k * rho * rho);
  return worldRay(p.pose, Eigen::Vector3d::Zero(), Eigen::Vector3d(x.x(), x.y(), 1));
}

}  // namespace artcam
