// SPDX-License-Identifier: Apache-2.0
// The classical cameras as object-space ARTcams (the paper's §1: the RTcam "subsumes the linear
// camera and many non-linear cameras as special cases", proven in [HCS*07]).
//
// Every camera here is a 4→4 position tensor (output blocks mirror input blocks, eq 3):
// z = x Q_i xᵀ for x = (X, Y, Z, 1) and the outputs, divided by z_4, are
//   (u, v, nearness, 1)
// - (u, v): the image point in the NORMALISED frame of the output image (frames.h: the larger
//   image side spans [-1, 1], v down), so one camera renders at any size;
// - nearness: larger is nearer along every ray, and > 0 exactly for the points the camera sees
//   (in front of it); the cloud renderer's z-buffer keeps the largest. For the pinhole it is
//   inverse depth W/Z.
// Each camera is written in camera coordinates (camera_pose.h: x right, y down, z forward) and
// moved by its pose. Each has its RAY DEFINITION beside it, written from the geometry and not
// from the tensor, so the tests can check one against the other: the image point of P is the
// point whose ray passes through P.
#pragma once

#include "core/cameras/camera_pose.h"
#include "core/model/camera.h"

#include <Eigen/Core>

#include <optional>

namespace artcam {

// Central projection: u = f·X/Z + cx, v = f·Y/Z + cy; z = ((fX + cxZ)W, (fY + cyZ)W, W², ZW).
struct PinholeParams {
  double focal = 2.0;  // normalised image units per unit of X/Z (f = 1/tan(half fov))
  Eigen::Vector2d principal = Eigen::Vector2d::Zero();
  CameraPose pose;
};
Camera pinholeCamera(const PinholeParams& p);
Ray pinholeRay(const PinholeParams& p, const Eigen::Vector2d& image);

// Parallel projection along z: u = s·X, v = s·Y; nearness 1 - Z/far (points beyond `far` are
// dropped; parallel rays have no "behind").
struct OrthographicParams {
  double scale = 0.5;  // image units per object unit
  double far = 1e6;
  CameraPose pose;
};
Camera orthographicCamera(const OrthographicParams& p);
Ray orthographicRay(const OrthographicParams& p, const Eigen::Vector2d& image);

// Linear push-broom [GH97]: a 1D perspective sensor swept along x. u = s·X (orthographic along
// the sweep), v = f·Y/Z (perspective across it): every ray meets the line of foci (the x axis)
// and is parallel to the plane x = const. z = (sXZ, fYW, W², ZW): quadratic numerators over
// the quadratic denominator ZW.
struct PushbroomParams {
  double focal = 2.0;  // across the sweep
  double scale = 0.5;  // along the sweep, image units per object unit
  CameraPose pose;
};
Camera pushbroomCamera(const PushbroomParams& p);
Ray pushbroomRay(const PushbroomParams& p, const Eigen::Vector2d& image);

// Crossed slits [ZFPW03]: every ray meets two lines, the slit {X = 0, Z = a} (parallel to y; it
// sets u) and the slit {Y = 0, Z = b} (parallel to x; it sets v):
// u = f·X/(Z - a), v = f·Y/(Z - b); z = (fX(Z - bW), fY(Z - aW), W², (Z - aW)(Z - bW)).
// Nearness 1/((Z - a)(Z - b)) is positive beyond both slits, where the scene must be.
struct XSlitParams {
  double focal = 2.0;
  double slit_u_depth = 0.0;   // a
  double slit_v_depth = -1.0;  // b
  CameraPose pose;
};
Camera xslitCamera(const XSlitParams& p);
Ray xslitRay(const XSlitParams& p, const Eigen::Vector2d& image);

// The rational-function lens of Claus & Fitzgibbon [CF05]: a central camera whose image point
// is a ratio of quadratics of the LIFTED ray direction χ(d) = (X², XY, Y², XZ, YZ, Z²):
// (u, v, 1) ~ A χ. (C&F write the same lifted rational function from pixel to ray; an ARTcam
// maps points forward, so the preset uses it in the projection direction, which is how the
// paper counts RFcams among RTcams.) Nearness Z·W / (A χ)_3.
Camera rationalLensCamera(const Eigen::Matrix<double, 3, 6>& a, const CameraPose& pose);

// Its radially symmetric member with closed-form rays, the division model:
// u = f·x / (1 + k|x|²) for x = (X/Z, Y/Z); k > 0 barrel, k < 0 pin-cushion.
struct RationalLensParams {
  double focal = 2.0;
  double k = 0.2;
  CameraPose pose;
};
Eigen::Matrix<double, 3, 6> rationalLensMatrix(const RationalLensParams& p);
Camera rationalLensCamera(const RationalLensParams& p);
// Empty outside the image of the lens (barrel: |u| ≤ f / (2√k)).
std::optional<Ray> rationalLensRay(const RationalLensParams& p, const Eigen::Vector2d& image);

}  // namespace artcam
