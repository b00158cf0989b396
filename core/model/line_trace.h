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

struct LineTrace {
  std::string label;                     // the CSV's `line` field; names the line in messages
  std::vector<Eigen::Vector2d> points;   // source pixels, in the order they were traced
  bool enabled = true;
};

}  // namespace artcam
