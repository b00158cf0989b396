// SPDX-License-Identifier: Apache-2.0
// The 3D effects of the paper's Fig 1 as object-space ARTcams: each maps a cloud point
// (X, Y, Z, 1) [and its colour (a·r, a·g, a·b, a)] to a moved point (X', Y', Z', 1) [and colour],
// so it is applied before a projecting camera (projective_cameras.h, glc.h) renders the cloud.
// All are single quadratic-form stages, as the paper sets them by typing numbers.
//
// Block layouts: position (4) alone, or position (4) then colour (4) when the geometry reads
// colour through the pc coupling (eq 6/7: Q_ipc; stored symmetrically, so every coupling is
// built with symmetricOuter, which halves the two off-diagonal blocks — eq 10).
#pragma once

#include "core/cameras/camera_pose.h"
#include "core/model/camera.h"

#include <Eigen/Core>

namespace artcam {

// Twist about the y axis (Fig 1, top middle): the cross-section at height Y turns by
// atan(rate·Y). A quadratic form cannot rotate without scaling: X' = X - rate·Y·Z,
// Z' = Z + rate·Y·X turns by that angle and scales the section by √(1 + rate²Y²).
struct TwistParams {
  double rate = 0.35;  // tan of the turn per unit height
};
Camera twistEffect(const TwistParams& p);

// Pin-cushion in 3D (Fig 1, top right): P' = c + (P - c) / (1 - k|P - c|²); points swell
// outwards faster the farther they are from the centre. k < 0 gives barrel. The pole sphere
// |P - c| = 1/√k must lie outside the object.
struct PincushionParams {
  double k = 0.12;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
Camera pincushionEffect(const PincushionParams& p);

// Inverse perspective (Fig 1, bottom left): objects magnify as they recede. For a viewer at
// `eye` looking at `target` (distance E), a point at depth t = Z_cam - E behind the target plane
// is scaled across the view by s = (t + E) / (E (1 - gain·t)), which cancels the viewer's
// perspective 1/(t + E) and replaces it by 1/(1 - gain·t): apparent size GROWS with depth.
// gain = 1/E mirrors ordinary perspective; the pole plane is t = 1/gain.
struct InversePerspectiveParams {
  Eigen::Vector3d eye{2.744, 2.058, -3.430};  // the default view of the sample cube
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double gain = 0.0;  // 0: 1/E
};
Camera inversePerspectiveEffect(const InversePerspectiveParams& p);

// Colour-controlled scale (Fig 1, bottom middle; the paper's eq 8/9 in 3D): warm colours expand
// the object and cold colours shrink it, P' = c + (P - c)(1 + s·(r - b)), through the pc
// coupling z_pos = X·(c₄ + s·c₁ - s·c₃), z_W = W·c₄ (premultiplied c, so r = c₁/c₄).
struct ColourScaleParams {
  double strength = 0.35;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
Camera colourScaleEffect(const ColourScaleParams& p);

// Chromatic aberration (Fig 1, bottom right; the paper's Fig 4 right and eq 8/9): each colour
// layer is scaled about the centre by 1 + s_red·r + s_green·g + s_blue·b. Rendered with the cloud
// split into its red, green and blue layers (cloud_render.h, RenderLayers::Rgb), each layer
// moves by its own s: the mis-registered prints of the paper.
struct ChromaticAberrationParams {
  double red = 0.06;
  double green = 0.0;
  double blue = -0.06;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
Camera chromaticAberrationEffect(const ChromaticAberrationParams& p);

}  // namespace artcam
