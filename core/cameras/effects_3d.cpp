// SPDX-License-Identifier: Apache-2.0
#include "core/cameras/effects_3d.h"

#include "core/model/frames.h"

#include <cmath>
#include <stdexcept>

namespace artcam {

using tensor4::linear;
using tensor4::product;

namespace {

// Moves an effect written about the origin to `centre`: x_local = x (translate by -c), and the
// outputs are translated back by +c.
void centreAt(Camera& camera, const Eigen::Vector3d& centre) {
  if (centre.isZero()) return;
  Eigen::Matrix4d to_local = Eigen::Matrix4d::Identity();  // row form: x_local = x * to_local
  to_local.block<1, 3>(3, 0) = -centre.transpose();
  changeInputFrame(camera, 0, to_local);
  Eigen::Matrix4d to_world = Eigen::Matrix4d::Identity();  // column form: y = A y_local
  to_world.block<3, 1>(0, 3) = centre;
  changeOutputFrame(camera, 0, to_world);
}

// Position (4) + colour (4): the tensors of an effect that reads colour in its geometry and
// leaves colour itself unchanged (colour outputs c_k·W, so c' = c and alpha' = alpha).
// `scale` is the linear form over the colour block that multiplies every coordinate.
Camera colourCoupledScale(const Eigen::Vector4d& scale, const Eigen::Vector3d& centre) {
  const int n = 8;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(8, i); };
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  s.tail<4>() = scale;
  Stage stage;
  for (int i = 0; i < 3; ++i) stage.q.push_back(symmetricOuter(e(i), s));  // eq 8/9: Q_ipc
  stage.q.push_back(symmetricOuter(e(3), e(7)));                           // W·c₄
  for (int i = 4; i < 8; ++i) stage.q.push_back(symmetricOuter(e(i), e(3)));
  Camera camera({Block{BlockKind::Position, 4}, Block{BlockKind::Colour, 4}}, {std::move(stage)},
                {}, {});
  centreAt(camera, centre);
  return camera;
}

}  // namespace

Camera twistEffect(const TwistParams& p) {
  const double r = p.rate;
  // Q_i = sym(l h): X·W - r·Y·Z, Y·W, Z·W + r·Y·X, W·W.
  return objectCamera(
      {product(tensor4::X(), tensor4::W()) - r * product(tensor4::Y(), tensor4::Z()),
       product(tensor4::Y(), tensor4::W()),
       product(tensor4::Z(), tensor4::W()) + r * product(tensor4::Y(), tensor4::X()),
       product(tensor4::W(), tensor4::W())},
      {});
}

Camera pincushionEffect(const PincushionParams& p) {
  Eigen::MatrixXd den = product(tensor4::W(), tensor4::W());
  for (int i = 0; i < 3; ++i) den(i, i) -= p.k;  // W² - k(X² + Y² + Z²)
  Camera camera =
      objectCamera({product(tensor4::X(), tensor4::W()), product(tensor4::Y(), tensor4::W()),
                    product(tensor4::Z(), tensor4::W()), den},
                   {});
  centreAt(camera, p.centre);
  return camera;
}

Camera inversePerspectiveEffect(const InversePerspectiveParams& p) {
  const CameraPose view = CameraPose::lookAt(p.eye, p.target, p.up);
  const double e = (p.target - p.eye).norm();
  const double g = p.gain != 0.0 ? p.gain : 1.0 / e;
  // In view coordinates: with den = E((1 + gE)W - gZ),
  // X' = X·Z/den, Y' = Y·Z/den, Z' = Z (z_Z = Z·den/W… written as Z·den over W·den).
  const Eigen::Vector4d den = e * linear(0, 0, -g, 1 + g * e);
  Camera camera({Block{BlockKind::Position, 4}},
                {Stage{{product(tensor4::X(), tensor4::Z()), product(tensor4::Y(), tensor4::Z()),
                        product(tensor4::Z(), den), product(tensor4::W(), den)}}},
                {}, {});
  changeInputFrame(camera, 0, view.rowMatrix());
  Eigen::Matrix4d world_from_view = Eigen::Matrix4d::Identity();  // column form
  world_from_view.topLeftCorner<3, 3>() = view.rotation.transpose();
  world_from_view.topRightCorner<3, 1>() = view.centre;
  changeOutputFrame(camera, 0, world_from_view);
  return camera;
}

Camera colourScaleEffect(const ColourScaleParams& p) {
  return colourCoupledScale(Eigen::Vector4d(p.strength, 0, -p.strength, 1), p.centre);
}

Camera chromaticAberrationEffect(const ChromaticAberrationParams& p) {
  return colourCoupledScale(Eigen::Vector4d(p.red, p.green, p.blue, 1), p.centre);
}

}  // namespace artcam
