// SPDX-License-Identifier: Apache-2.0
// The 3D effects of the paper's Fig 1 (core/cameras/effects_3d.h), one table beside the image
// one (effect_table.h): what `artcam preset NAME`, `artcam preset list` and `artcam preset
// --help` offer for them, and the studio's 3D view list (ui/cloud_view.h). A row holds the
// effect's name, its human name, a one-line summary, its parameters (effect_param.h, the type
// the image table uses: defaults, ranges, units), whether it is rendered with the cloud split
// into colour layers, whether its eye and target are the viewer's, and its builder.
//
// Decisions:
// - The object frame. Every parameter is in the units of an ObjectFrame: origin at its centre,
//   1 = its radius, as the image effects' parameters are in the photo's normalised frame. So one
//   default suits any cloud: a twist's rate is its turn one radius above the centre, a
//   pincushion's k puts the pole sphere 1/√k radii from its centre, a position such as `centre`
//   is an offset in radii. The 3D view builds every effect in the frame of its cloud's bounds
//   (centre and bounding radius); the CLI's frame is --object-centre and --object-radius,
//   default the origin and 1, in which the numbers are plain object units (the cameras `artcam
//   preset` always wrote). This rule replaces the 3D view's own scaling of the defaults.
// - Viewer rows (inverse perspective): `eye` and `at` are the viewer's and the point it looks
//   at; the 3D view puts them at its orbit's eye and its cloud's centre. Their defaults are the
//   sample cube's default view (cloud_render.h defaultViewPose), as the view cameras' are.
// - Ranges bound what the camera is meant for, as in the image table (a value outside is
//   refused, never clamped): a pincushion's k ≤ 0.9 keeps its pole sphere outside the unit
//   sphere about its centre; colour-scale's |strength| < 1 and the aberration's per-layer
//   |s| ≤ 0.3 keep every colour's scale positive.
#pragma once

#include "core/effects/effect_param.h"
#include "core/model/camera.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

// Where a 3D effect's parameters live: world = centre + radius · (frame coordinates).
struct ObjectFrame {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 1.0;

  Eigen::Vector3d fromWorld(const Eigen::Vector3d& world) const {
    return (world - centre) / radius;
  }
};

struct Effect3dSpec {
  std::string name;     // the CLI's preset name: "twist-3d"
  std::string label;    // the studio's human name: "Twist"
  std::string summary;  // one line for listings and tooltips
  std::vector<EffectParam> params;
  // The camera in frame units; `values` holds every parameter of the row, each checked against
  // it. Throws std::invalid_argument for values the camera refuses (an eye on its target).
  Camera (*build)(const EffectValues& values) = nullptr;
  // Rendered with the cloud split into its red, green and blue layers, each moved by its own
  // colour (artcam render --layers rgb; cloud_render.h RenderLayers::Rgb).
  bool colour_layers = false;
  // `eye` and `at` are the viewer's (see the decisions above).
  bool viewer = false;
};

const std::vector<Effect3dSpec>& effect3dSpecs();
const Effect3dSpec* findEffect3d(const std::string& name);

// The row's camera in `frame`: the defaults filled in for missing parameters, built in frame
// units, then moved to the world (x_frame = (x − centre)/radius in, the inverse out). Throws
// std::invalid_argument for an unknown effect or parameter, a value out of range, a frame whose
// radius is not positive and finite, or values the camera refuses.
Camera buildEffect3d(const std::string& name, const EffectValues& values,
                     const ObjectFrame& frame = {});

}  // namespace artcam
