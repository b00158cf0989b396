// SPDX-License-Identifier: Apache-2.0
// A small command-line parser: positional arguments and --options (with or without a value).
// Usage errors throw UsageError, which the dispatcher prints in at most three lines: the error,
// its hint ("did you mean --filter?") if any, and "see 'artcam CMD --help'".
#pragma once

#include "core/model/camera.h"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace artcam::cli {

struct UsageError : std::runtime_error {
  explicit UsageError(const std::string& message, std::string hint_line = {})
      : std::runtime_error(message), hint(std::move(hint_line)) {}
  std::string hint;  // one line, e.g. "did you mean --filter?"; empty: none
};

struct OptionSpec {
  std::string name;       // "--size"
  std::string short_name; // "-o" or empty
  bool takes_value = false;
};

class Args {
 public:
  Args(const std::vector<std::string>& argv, const std::vector<OptionSpec>& specs);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const;
  std::string valueOr(const std::string& name, const std::string& fallback) const;
  // Throws UsageError unless exactly `count` positionals were given.
  void expectPositional(size_t count, const std::string& what) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

// The one size spelling of the command line is "WxH" (also "WXH"). `legacy_comma` also takes
// "W,H", for the options that took it before WxH was everywhere (preset --size). Throws
// UsageError naming the option.
FrameSize parseSize(const std::string& text, const std::string& option, bool legacy_comma = false);

// The name a mistyped `typed` most likely meant: the one candidate of which it is a prefix, or
// else the one candidate nearest by optimal-string-alignment (Damerau–Levenshtein) distance
// when that is at most 2 and shorter than the word; leading dashes are ignored ("-filter",
// "--filtr" → "--filter"). Empty when there is none or several are equally near, so a hint
// never guesses between two.
std::string closestName(const std::string& typed, const std::vector<std::string>& candidates);
// "did you mean X?" for closestName, or empty.
std::string didYouMean(const std::string& typed, const std::vector<std::string>& candidates);

}  // namespace artcam::cli
