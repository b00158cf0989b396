// SPDX-License-Identifier: Apache-2.0
// Where a camera stands in object space, and the helpers that build object-space tensors.
//
// Conventions:
// - Camera coordinates: x right, y DOWN, z forward (the image's v grows downwards, as in
//   docs/architecture.md, "Frames and pixels"). A pose maps world to camera:
//   P_cam = R (P_world - C).
// - The family cameras (projective_cameras.h, glc.h) and the 3D effects are written in camera
//   (or local) coordinates and moved into the world by substituting the input row vector,
//   x_cam = x_world H_row, so Q_i <- H_row Q_i H_rowᵀ (frames.h changeInputFrame).
// - Object-space tensors act on rows (X, Y, Z, W); `linear(a, b, c, d)` names the linear form
//   aX + bY + cZ + dW, and `product(l, m)` the symmetric Q with x Q xᵀ = (x·l)(x·m).
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

namespace artcam {

struct CameraPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // camera_from_world
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();        // in world coordinates

  // Looks from `eye` at `target`; `up` (world) appears upwards in the image. Throws
  // std::invalid_argument when eye == target or up is parallel to the viewing direction.
  static CameraPose lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                           const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());

  Eigen::Vector3d cameraFromWorld(const Eigen::Vector3d& p) const {
    return rotation * (p - centre);
  }
  Eigen::Vector3d worldFromCamera(const Eigen::Vector3d& p) const {
    return rotation.transpose() * p + centre;
  }
  // x_cam = x_world * rowMatrix() for homogeneous rows (X, Y, Z, W).
  Eigen::Matrix4d rowMatrix() const;
  bool isIdentity() const;
};

// A ray in world coordinates: origin + t·direction.
struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;

  // Distance from p to the infinite line of the ray.
  double distanceTo(const Eigen::Vector3d& p) const;
};

namespace tensor4 {

Eigen::Vector4d linear(double x, double y, double z, double w);
inline Eigen::Vector4d X() { return linear(1, 0, 0, 0); }
inline Eigen::Vector4d Y() { return linear(0, 1, 0, 0); }
inline Eigen::Vector4d Z() { return linear(0, 0, 1, 0); }
inline Eigen::Vector4d W() { return linear(0, 0, 0, 1); }
Eigen::MatrixXd product(const Eigen::VectorXd& l, const Eigen::VectorXd& m);

}  // namespace tensor4

// A position-only object camera (one 4×4 block) from its four tensors, moved by `pose`.
Camera objectCamera(const std::vector<Eigen::MatrixXd>& q_camera, const CameraPose& pose);

}  // namespace artcam
