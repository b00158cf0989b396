// SPDX-License-Identifier: Apache-2.0
// Where artcam fit's matches come from: a matches CSV, or an ST map sampled on a grid
// (fit --stmap). Both fit paths (single camera, --piecewise) read through this, so a map made
// elsewhere fits exactly as clicked or tracked matches do.
#pragma once

#include "core/model/fit_record.h"

#include <functional>
#include <string>
#include <vector>

namespace artcam::cli {

struct MatchInput {
  std::string name;  // the file named in errors and never overwritten
  // The matches in pixels; throws CommandError with one line naming the file.
  std::function<std::vector<PointMatch>()> read;
};

}  // namespace artcam::cli
