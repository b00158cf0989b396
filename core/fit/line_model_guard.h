// SPDX-License-Identifier: Apache-2.0
// What Auto for straight lines checks before it trusts a camera beyond the radial lens
// (fit_lines.h). Lines fix a camera only up to what keeps them straight: with horizontal and
// vertical edges alone, a quadratic can stretch v into v + b v² or lean u into u + a uv and
// every edge stays straight, so a candidate that straightens the traced edges a little better
// can still put a keystone or a stretch into the picture, or pull the photo off part of the
// frame. These measures compare a candidate with the radial lens fitted to the same lines, whose
// one parameter cannot do either. Points are source and target pixels (centres at i + 0.5).
#pragma once

#include "core/model/camera.h"

namespace artcam {

// The largest relative change of the local spacing along the frame's rows and columns,
// |∂y/∂u| and |∂y/∂v| of `candidate` against `reference`, over a 9×7 grid of the source frame:
// 0 for the same map, 0.3 where one puts grid rows 30 % further apart than the other. Infinity
// when either camera leaves a grid point unmapped (its pole).
double spacingChange(const Camera& candidate, const Camera& reference);

// The fraction of the target frame that the photo covers through the camera (1: no empty area),
// from the source frame sampled three times per target cell of 1/64 of the frame's long side.
double frameCoverage(const Camera& camera);

}  // namespace artcam
