// SPDX-License-Identifier: Apache-2.0
#include "core/effects/chromatic.h"

#include <Eigen/Core>

namespace artcam {

namespace {

using namespace layout_pc;

Eigen::VectorXd unit(int i) { return Eigen::VectorXd::Unit(kN, i); }

// The colour outputs of layer `channel`: its channel and alpha times p3 (the identity's unit
// element, camera.h), the other two channels zero.
void selectChannel(Stage& stage, int channel) {
  for (int k = 0; k < 3; ++k)
    stage.q[kR + k] = k == channel ? symmetricOuter(unit(kR + k), unit(kW))
                                   : Eigen::MatrixXd::Zero(kN, kN);
  stage.q[kA] = symmetricOuter(unit(kA), unit(kW));
}

std::vector<Block> blocks() { return {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}}; }

}  // namespace

std::vector<Camera> rgbShiftLayers(const RgbShiftParams& p, FrameSize source, FrameSize target) {
  std::vector<Camera> layers;
  for (int k = 0; k < 3; ++k) {
    Stage stage;
    stage.q.assign(kN, Eigen::MatrixXd::Zero(kN, kN));
    const double m = 1.0 + p.scale[static_cast<size_t>(k)];
    // u' = m·u + dx, v' = m·v + dy over w' = w: linear maps lifted by the unit element w.
    stage.q[kU] = symmetricOuter(m * unit(kU) + p.dx[static_cast<size_t>(k)] * unit(kW), unit(kW));
    stage.q[kV] = symmetricOuter(m * unit(kV) + p.dy[static_cast<size_t>(k)] * unit(kW), unit(kW));
    stage.q[kW] = symmetricOuter(unit(kW), unit(kW));
    selectChannel(stage, k);
    layers.emplace_back(blocks(), std::vector<Stage>{stage}, source, target);
  }
  return layers;
}

std::vector<Camera> colourShiftLayers(const ColourShiftParams& p, FrameSize source,
                                      FrameSize target) {
  std::vector<Camera> layers;
  for (int k = 0; k < 3; ++k) {
    Stage stage;
    stage.q.assign(kN, Eigen::MatrixXd::Zero(kN, kN));
    // eq 8: z_1 = p1·(s_k·c_k + c4); eq 9: z_2 = p2·(s_k·c_k + c4); z_3 = p3·c4.
    const Eigen::VectorXd scale = p.s[static_cast<size_t>(k)] * unit(kR + k) + unit(kA);
    stage.q[kU] = symmetricOuter(unit(kU), scale);
    stage.q[kV] = symmetricOuter(unit(kV), scale);
    stage.q[kW] = symmetricOuter(unit(kW), unit(kA));
    selectChannel(stage, k);
    layers.emplace_back(blocks(), std::vector<Stage>{stage}, source, target);
  }
  return layers;
}

}  // namespace artcam
