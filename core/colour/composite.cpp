// SPDX-License-Identifier: Apache-2.0
#include "core/colour/composite.h"

#include <cmath>
#include <stdexcept>

namespace artcam {

namespace {

// The coefficients of z_k = a·A_k·w + b·B_k·w + cA·A_k·α_B + cB·B_k·α_A + p·A_k·B_k
// (composite.h's table).
struct Form {
  double a = 0, b = 0, c_a = 0, c_b = 0, p = 0;
};

Form formOf(CompositeOp op) {
  switch (op) {
    case CompositeOp::Over: return {1, 1, 0, -1, 0};
    case CompositeOp::Under: return {1, 1, -1, 0, 0};
    case CompositeOp::In: return {0, 0, 1, 0, 0};
    case CompositeOp::Out: return {1, 0, -1, 0, 0};
    case CompositeOp::Atop: return {0, 1, 1, -1, 0};
    case CompositeOp::Xor: return {1, 1, -1, -1, 0};
    case CompositeOp::Add: return {1, 1, 0, 0, 0};
    case CompositeOp::Multiply: return {1, 1, -1, -1, 1};
    case CompositeOp::Screen: return {1, 1, 0, 0, -1};
    case CompositeOp::Mix: return {0, 1, 0, 0, 0};
  }
  return {};
}

}  // namespace

const std::vector<std::string>& compositeOpNames() {
  static const std::vector<std::string> names = {"over", "under", "in",       "out",    "atop",
                                                 "xor",  "add",   "multiply", "screen", "mix"};
  return names;
}

std::string_view compositeOpName(CompositeOp op) {
  return compositeOpNames().at(static_cast<size_t>(op));
}

std::optional<CompositeOp> compositeOpFromName(std::string_view name) {
  const std::vector<std::string>& names = compositeOpNames();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<CompositeOp>(i);
  return std::nullopt;
}

Camera compositeCamera(CompositeOp op, double amount, FrameSize frame) {
  if (!(amount >= 0.0 && amount <= 1.0))
    throw std::invalid_argument("the composite's amount must lie in [0, 1]");
  if (!frame.isImage()) throw std::invalid_argument("a composite needs an image frame");
  const std::vector<Block> blocks = {
      {BlockKind::Position, 3}, {BlockKind::Colour, 4}, {BlockKind::SecondColour, 4}};
  // Element indices: position u v w = 0..2, A = 3..6, B = 7..10.
  constexpr int kW = 2, kA = 3, kB = 7, kN = 11, kAlpha = 3;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  // The identity (z_i = x_i·w) everywhere, then the colour outputs replaced.
  Camera camera = Camera::identity(blocks, frame, frame);
  Stage& stage = camera.stages()[0];
  const Form f = formOf(op);
  const double t = amount;
  for (int k = 0; k < 4; ++k) {
    const Eigen::VectorXd a_k = e(kA + k), b_k = e(kB + k);
    // eq 3 with symmetric storage (eq 10): symmetricOuter(l, h) is the form (x·l)(x·h).
    Eigen::MatrixXd q = (1.0 - t) * symmetricOuter(a_k, e(kW));  // the photo kept: (1 − t)·A
    q += t * (f.a * symmetricOuter(a_k, e(kW)) + f.b * symmetricOuter(b_k, e(kW)) +
              f.c_a * symmetricOuter(a_k, e(kB + kAlpha)) +
              f.c_b * symmetricOuter(b_k, e(kA + kAlpha)) + f.p * symmetricOuter(a_k, b_k));
    stage.q[static_cast<size_t>(kA + k)] = q;
  }
  camera.validate();
  return camera;
}

}  // namespace artcam
