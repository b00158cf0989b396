// SPDX-License-Identifier: Apache-2.0
// Image-space (2D) position cameras for the presets: RTcams over (u, v, 1) in the normalised
// frame of `frame` (frames.h: the larger side spans [-1, 1], v down), source = target frame.
#pragma once

#include "core/model/camera.h"

namespace artcam {

// y = p / (1 − k·|p|²): k > 0 pincushion (the edges swell), k < 0 barrel. z_w = w² − k(u² + v²);
// the pole circle |p| = 1/√k must lie outside the frame (refused otherwise).
Camera radialLensCamera(double k, FrameSize frame);

// The paper's Fig 1 twist in the picture plane (X' = X − rate·Y·Z with the roles of Y, Z taken
// by v, u): v' = v + rate·u·v, u' = u, so each row turns by atan(rate·v) about the centre
// column, the farther from the centre row the more. Polynomial: no pole.
Camera twistCamera(double rate, FrameSize frame);

// Inverse perspective in the picture (Fig 1's effect for a ground plane seen from above the
// horizon): the homography p' = p / (1 + gain·v) magnifies the upper (far) rows. Pole line
// v = −1/gain, refused if it crosses the frame.
Camera inversePerspectiveCamera(double gain, FrameSize frame);

}  // namespace artcam
