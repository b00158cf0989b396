// SPDX-License-Identifier: Apache-2.0
// Where artcam fit's matches come from: a matches CSV, or an ST map sampled on a grid
// (fit --stmap). Both fit paths (single camera, --piecewise) read through this, so a map made
// elsewhere fits exactly as clicked or tracked matches do.
#pragma once

#include "app/cli/args.h"
#include "core/fit/options_check.h"
#include "core/model/fit_record.h"

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace artcam::cli {

struct MatchInput {
  std::string name;  // the file named in errors and never overwritten
  // The matches in pixels; throws CommandError with one line naming the file.
  std::function<std::vector<PointMatch>()> read;
};

// The fit's own range check (FitOptions::check and the like, core/fit/options_check.h), run
// before any work: the option parses keep the same ranges, so this refuses only what they let
// through, as a usage error naming the option that set the field (`option_of`: field → option).
template <class Options>
void checkFitOptions(const Options& options,
                     std::initializer_list<std::pair<std::string_view, const char*>> option_of) {
  const Status s = options.check([option_of](std::string_view field) -> std::string {
    for (const auto& [f, option] : option_of)
      if (f == field) return option;
    return {};
  });
  if (!s) throw UsageError(s.message);
}

}  // namespace artcam::cli
