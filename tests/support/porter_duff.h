// SPDX-License-Identifier: Apache-2.0
// The Porter–Duff operators on premultiplied colours (a·r, a·g, a·b, a), written out from their
// definitions for the compositing tests to check the colour block's quadratic forms against
// (core/colour/composite.h): alpha by the same rule as the colours where the definition is per
// element; the separable blend modes multiply and screen with the union alpha aA + aB − aA·aB.
#pragma once

#include "core/colour/composite.h"

#include <Eigen/Core>

#include <array>

namespace artcam::test {

using PremultipliedColour = Eigen::Vector4d;

PremultipliedColour porterDuff(CompositeOp op, const PremultipliedColour& a,
                               const PremultipliedColour& b);

inline constexpr std::array<CompositeOp, 10> kCompositeOps = {
    CompositeOp::Over, CompositeOp::Under,    CompositeOp::In,     CompositeOp::Out,
    CompositeOp::Atop, CompositeOp::Xor,      CompositeOp::Add,    CompositeOp::Multiply,
    CompositeOp::Screen, CompositeOp::Mix};

}  // namespace artcam::test
