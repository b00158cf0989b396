// SPDX-License-Identifier: Apache-2.0
#include "core/cameras/camera_pose.h"

#include "core/model/frames.h"

#include <Eigen/Geometry>

#include <stdexcept>

namespace artcam {

CameraPose CameraPose::lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                              const Eigen::Vector3d& up) {
  const Eigen::Vector3d forward = target - eye;
  if (!(forward.norm() > 0)) throw std::invalid_argument("lookAt: eye and target coincide");
  const Eigen::Vector3d z = forward.normalized();
  // Camera y points down in the image: minus the part of `up` across the view.
  const Eigen::Vector3d down = -(up - up.dot(z) * z);
  if (!(down.norm() > 1e-12 * up.norm()))
    throw std::invalid_argument("lookAt: up is parallel to the viewing direction");
  const Eigen::Vector3d y = down.normalized();
  const Eigen::Vector3d x = y.cross(z);  // right-handed: x × y = z
  CameraPose pose;
  pose.rotation.row(0) = x.transpose();
  pose.rotation.row(1) = y.transpose();
  pose.rotation.row(2) = z.transpose();
  pose.centre = eye;
  return pose;
}

Eigen::Matrix4d CameraPose::rowMatrix() const {
  // Column form [R, -R C; 0, 1], transposed for rows.
  Eigen::Matrix4d col = Eigen::Matrix4d::Identity();
  col.topLeftCorner<3, 3>() = rotation;
  col.topRightCorner<3, 1>() = -rotation * centre;
  return col.transpose();
}

bool CameraPose::isIdentity() const {
  return rotation == Eigen::Matrix3d::Identity() && centre == Eigen::Vector3d::Zero();
}

double Ray::distanceTo(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = direction.normalized();
  const Eigen::Vector3d v = p - origin;
  return (v - v.dot(d) * d).norm();
}

namespace tensor4 {

Eigen::Vector4d linear(double x, double y, double z, double w) { return {x, y, z, w}; }

Eigen::MatrixXd product(const Eigen::VectorXd& l, const Eigen::VectorXd& m) {
  return symmetricOuter(l, m);
}

}  // namespace tensor4

Camera objectCamera(const std::vector<Eigen::MatrixXd>& q_camera, const CameraPose& pose) {
  Camera camera({Block{BlockKind::Position, 4}}, {Stage{q_camera}}, {}, {});
  if (!pose.isIdentity()) changeInputFrame(camera, 0, pose.rowMatrix());
  return camera;
}

}  // namespace artcam
