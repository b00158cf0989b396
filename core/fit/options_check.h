// SPDX-License-Identifier: Apache-2.0
// The range checks of the fit options (FitOptions::check, ColourFitOptions::check,
// LinesFitOptions::check). A check names the first field outside its range, the range and the
// value, in the caller's words where it gives them: the CLI names its options, so a refusal
// reads "--threshold must be a number above 0, got -1". The fit entry points run the same check
// and return its failure as their status, so every caller, the studio included, is held to
// the ranges; the CLI runs it first only to refuse with exit status 2 before any work.
#pragma once

#include "core/model/status.h"

#include <functional>
#include <limits>
#include <string>
#include <string_view>

namespace artcam {

// A field's name as the caller's user knows it ("robust_threshold_px" → "--threshold"); empty,
// or an empty answer: the field's own name.
using FieldNames = std::function<std::string(std::string_view field)>;

// Checks fields in turn and keeps the first failure:
//   return OptionsCheck(names)
//       .number("click_sigma_px", click_sigma_px, 0, kNoBound, Ends::AboveMin)
//       .whole("restarts", restarts, 0, 1000)
//       .status();
class OptionsCheck {
 public:
  enum class Ends { Closed, AboveMin };  // min itself allowed, or only numbers above it
  static constexpr double kNoBound = std::numeric_limits<double>::infinity();

  explicit OptionsCheck(const FieldNames& names) : names_(names) {}
  // Finite and within [min, max] (or (min, max]).
  OptionsCheck& number(std::string_view field, double value, double min, double max,
                       Ends ends = Ends::Closed);
  OptionsCheck& whole(std::string_view field, long long value, long long min, long long max);
  // For enumerations: `valid` false means the value (`as_integer`) is none of `choices`
  // ("auto, radial or quadratic"), as a cast from an integer can make it.
  OptionsCheck& oneOf(std::string_view field, bool valid, std::string_view choices, int as_integer);
  Status status() const { return status_; }

 private:
  std::string name(std::string_view field) const;
  void fail(std::string_view field, const std::string& rule, const std::string& value);

  const FieldNames& names_;
  Status status_ = Status::success();
};

}  // namespace artcam
