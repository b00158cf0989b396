// SPDX-License-Identifier: Apache-2.0
// The image effects, one table: what `artcam preset NAME`, `artcam preset list`, `artcam preset
// --help`, the manual page and the studio's effects panel offer, and the builder that makes each
// effect's camera. A row holds the effect's name, its human name, a one-line summary, its
// parameters (effect_param.h: name, number or vector of N numbers, range, default, unit),
// whether it reads depth, and its builder. The tensor panel's presets are rows of it too.
//
// Adding an effect: its camera function (e.g. image_warps.h), one row in effect_table.cpp that
// calls it, and its test. The CLI options (--NAME VALUE, vectors comma-separated), the panel's
// spin boxes, the listings and the range checks all come from the row.
//
// Decisions:
// - Parameter names are the CLI's (what users' scripts already pass): the haze colour is one
//   vector `haze` (--haze r,g,b), chromatic aberration keeps its per-channel shifts red-dx ….
// - A range bounds every component of a parameter; a value outside it is refused (the CLI says
//   which parameter and its range), never clamped, so a camera is never silently different from
//   what was asked. Ranges stay where the camera accepts every frame: the radial lens refuses
//   k·|p|² ≥ 0.95 and |p|² ≤ 2 in the normalised frame, so k ≤ 0.45; inverse perspective refuses
//   |gain·v| ≥ 0.9 and |v| ≤ 1, so |gain| ≤ 0.85 (image_warps.h).
// - Compositing (composite.h) is a row whose camera reads a second image (needs_second), with
//   its operator a named choice; the studio has no second image yet, so its effect stack leaves
//   such a row out with a note, as it leaves out depth effects without depth.
// - Builders return the whole camera value (model/artcam.h): chromatic aberration is three
//   layers, depth of field a depth output that is the blur variance.
#pragma once

#include "core/effects/effect_param.h"
#include "core/model/artcam.h"
#include "core/model/camera.h"

#include <string>
#include <vector>

namespace artcam {

struct EffectSpec {
  std::string name;     // the CLI's preset name and the project file's: "barrel"
  std::string label;    // the studio's human name: "Barrel", "Depth of field"
  std::string summary;
  std::vector<EffectParam> params;
  bool needs_depth = false;
  // `values` holds every parameter of the row, each checked against it. Throws
  // std::invalid_argument for a value the camera refuses (e.g. near ≥ far, a pole in the frame).
  Artcam (*build)(const EffectValues& values, FrameSize frame) = nullptr;
  // The camera composites a second image (a second-colour block): artcam warp --second FILE.
  bool needs_second = false;
};

const std::vector<EffectSpec>& effectSpecs();
const EffectSpec* findEffect(const std::string& name);
const EffectParam* findParam(const EffectSpec& effect, const std::string& name);
// The human name users read ("General linear view" for photo-glc): the studio's lists and
// messages and `artcam preset list`. The name itself for an effect the table does not have.
std::string effectLabel(const std::string& name);

// The row's builder with the defaults filled in for missing parameters. Throws
// std::invalid_argument for an unknown effect or parameter, a value checkEffectValue refuses,
// or one the camera refuses.
Artcam buildEffect(const std::string& name, const EffectValues& values, FrameSize frame);

}  // namespace artcam
