// SPDX-License-Identifier: Apache-2.0
// A straight edge traced in a photo: points clicked or detected along one edge that is straight
// in the scene (a door frame, a horizon), in SOURCE pixels (centres at i + 0.5, y down). A lens
// calibration from lines (core/fit/fit_lines.h) looks for the camera that makes every traced
// edge straight again. Lives in the model layer because the fit, the files and the studio's
// project all speak it.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

// What a line is in the scene, when the user says so: a level edge (a horizon, a cornice) or a
// plumb one (a door frame). A role is a check, not a constraint: the fit straightens every line
// alike (so a lines file without roles makes the same camera) and reports how far each line
// with a role is tilted from its direction afterwards.
enum class LineRole { None, Horizontal, Vertical };

struct LineTrace {
  std::string label;                     // the CSV's `line` field; names the line in messages
  std::vector<Eigen::Vector2d> points;   // source pixels, in the order they were traced
  bool enabled = true;
  LineRole role = LineRole::None;
};

}  // namespace artcam
