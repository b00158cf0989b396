// SPDX-License-Identifier: Apache-2.0
#include "core/fit/options_check.h"

#include "core/util/number_text.h"

#include <cmath>
#include <cstdio>

namespace artcam {

std::string OptionsCheck::name(std::string_view field) const {
  std::string given = names_ ? names_(field) : std::string();
  return given.empty() ? std::string(field) : given;
}

void OptionsCheck::fail(std::string_view field, const std::string& rule, const std::string& value) {
  if (!status_) return;  // the first failure is the one reported
  status_ = Status::failure(name(field) + " must be " + rule + ", got " + value);
}

OptionsCheck& OptionsCheck::number(std::string_view field, double value, double min, double max,
                                   Ends ends) {
  const bool above = ends == Ends::AboveMin;
  const bool ok = std::isfinite(value) && (above ? value > min : value >= min) && value <= max;
  if (ok) return *this;
  std::string rule = "a number ";
  if (!above && std::isfinite(max))
    rule += "from " + numberText(min) + " to " + numberText(max);
  else
    rule += (above ? "above " : "of at least ") + numberText(min) +
            (std::isfinite(max) ? ", at most " + numberText(max) : "");
  fail(field, rule, numberText(value));
  return *this;
}

OptionsCheck& OptionsCheck::whole(std::string_view field, long long value, long long min,
                                  long long max) {
  if (value < min || value > max)
    fail(field, "a whole number from " + std::to_string(min) + " to " + std::to_string(max),
         std::to_string(value));
  return *this;
}

OptionsCheck& OptionsCheck::oneOf(std::string_view field, bool valid, std::string_view choices,
                                  int as_integer) {
  if (!valid) fail(field, "one of " + std::string(choices), std::to_string(as_integer));
  return *this;
}

}  // namespace artcam
