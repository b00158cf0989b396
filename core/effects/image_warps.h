// SPDX-License-Identifier: Apache-2.0
// Image-space (2D) position cameras for the presets: RTcams over (u, v, 1) in the normalised
// frame of `frame` (frames.h: the larger side spans [-1, 1], v down), source = target frame.
#pragma once

#include "core/model/camera.h"

namespace artcam {

// y = p / (1 − k·|p|²): k > 0 pincushion (the edges swell), k < 0 barrel. z_w = w² − k(u² + v²);
// the pole circle |p| = 1/√k must lie outside the frame (refused otherwise).
Camera radialLensCamera(double k, FrameSize frame);

// A lens's distortion with its own strengths, about a centre c (normalised), then a scale s:
// q = p − c, q₁ = q/(1 − k1·|q|²) (the radial lens above, about c), q₂ = q₁/(1 − k2·|q₁|²),
// p' = c + s·q₂. One quadratic stage when k2 = 0, else two chained (eq 3 per stage, the second
// fed the first's divided output), so p'/p = 1 + (k1 + k2) r² + (k1² + 3·k1·k2 + k2²) r⁴ + …:
// k2 shapes the rim as a fourth-order term does. Each stage's pole circle must lie outside
// what it is fed (the frame, then the first stage's image of it): refused otherwise.
struct LensDistortion {
  double k1 = 0.0, k2 = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double scale = 1.0;
};
Camera lensDistortionCamera(const LensDistortion& lens, FrameSize frame);

// The paper's Fig 1 twist in the picture plane (X' = X − rate·Y·Z with the roles of Y, Z taken
// by v, u): v' = v + rate·u·v, u' = u, so each row turns by atan(rate·v) about the centre
// column, the farther from the centre row the more. Polynomial: no pole.
Camera twistCamera(double rate, FrameSize frame);

// Inverse perspective in the picture (Fig 1's effect for a ground plane seen from above the
// horizon): the homography p' = p / (1 + gain·v) magnifies the upper (far) rows. Pole line
// v = −1/gain, refused if it crosses the frame.
Camera inversePerspectiveCamera(double gain, FrameSize frame);

}  // namespace artcam
