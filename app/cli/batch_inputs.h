// SPDX-License-Identifier: Apache-2.0
// artcam batch's list of work: inputs (files, or frame sequences written as a printf-style
// pattern "frame_%04d.png") and the output each one goes to.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace artcam::cli {

struct BatchNaming {
  std::string folder;  // -o DIR
  std::string suffix;  // --suffix: added to the input's stem
  std::string format;  // --format: the output's extension (no dot); empty: the input's
};

struct BatchItem {
  std::string input;
  std::string output;
};

// Frame numbers (--first and up) stay within ±kMaxFrameNumber, far from overflowing as they
// count up; %0Nd pads to at most kMaxFramePadding digits, more than any frame number has, so
// a width such as %099999999999999999999d is a mistake to refuse, not a name to build.
constexpr long kMaxFrameNumber = 1000000000;
constexpr int kMaxFramePadding = 32;

// Expands "name_%04d.ext" (one %d, optionally %0Nd; "%%" for a literal %) from `first` upward
// until a number has no file (first: 0, or 1 when there is no frame 0). Other arguments are
// taken as they are. Throws UsageError for a malformed pattern, CommandError when a pattern
// matches no file.
std::vector<std::string> expandBatchInputs(const std::vector<std::string>& arguments,
                                           std::optional<long> first);

// The output of each input; throws CommandError when two inputs would write one output.
// (Outputs that are inputs or exist already: outputs.h, checked by the command.)
std::vector<BatchItem> planBatch(const std::vector<std::string>& inputs, const BatchNaming& naming);

}  // namespace artcam::cli
