// SPDX-License-Identifier: Apache-2.0
// A small command-line parser: positional arguments and --options (with or without a value).
// Usage errors throw UsageError, which the dispatcher prints in at most three lines: the error,
// its hint ("did you mean --filter?") if any, and "see 'artcam CMD --help'".
#pragma once

#include "core/model/camera.h"

#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
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
// WxH where one side may be 0, "the other by the output's aspect" ("300x0", "0x200"); both 0
// is refused (that is the default, said by leaving the option out). UsageError otherwise.
FrameSize parseSizeByAspect(const std::string& text, const std::string& option);

// Numbers on the command line have one spelling, so every option refuses the same things:
// the WHOLE text is the number (std::from_chars: no leading space or '+', no trailing unit, no
// hex), finite, and within the option's range. Otherwise a UsageError names the option, the
// range and the text given, in the CLI's words:
//   --threads expects a whole number from 0 to 1024, got "2x"
//   --max-error expects a number above 0, got "1px"
// An infinite end is no bound ("above 0"); `Ends` says whether a finite end itself is taken.
enum class Ends { Closed, OpenMin, OpenMax, Open };
constexpr double kUnbounded = std::numeric_limits<double>::infinity();

long long parseInteger(std::string_view text, const std::string& option, long long min,
                       long long max);
double parseNumber(std::string_view text, const std::string& option, double min, double max,
                   Ends ends = Ends::Closed);
// Comma-separated lists of the same ("1,2", one number is a list of one; an empty item is
// refused): --threads expects comma-separated whole numbers from 1 to 1024, got "1,2x".
std::vector<long long> parseIntegerList(std::string_view text, const std::string& option,
                                        long long min, long long max);
std::vector<double> parseNumberList(std::string_view text, const std::string& option, double min,
                                    double max, Ends ends = Ends::Closed);
// The option's value parsed as above, or `fallback` when the option is not given.
int intOption(const Args& args, const std::string& option, int fallback, int min, int max);
double numberOption(const Args& args, const std::string& option, double fallback, double min,
                    double max, Ends ends = Ends::Closed);
// The same spelling for text that is not the user's (another program's output): the number,
// or nothing.
std::optional<long long> readInteger(std::string_view text);
std::optional<double> readNumber(std::string_view text);

// Worker threads an option may ask for (0: all cores). More than any machine this runs on
// has, so a slip such as --threads 20000 is refused instead of starting 20000 threads.
constexpr int kMaxThreads = 1024;

// The name a mistyped `typed` most likely meant: the one candidate of which it is a prefix, or
// else the one candidate nearest by optimal-string-alignment (Damerau–Levenshtein) distance
// when that is at most 2 and shorter than the word; leading dashes are ignored ("-filter",
// "--filtr" → "--filter"). Empty when there is none or several are equally near, so a hint
// never guesses between two.
std::string closestName(const std::string& typed, const std::vector<std::string>& candidates);
// "did you mean X?" for closestName, or empty.
std::string didYouMean(const std::string& typed, const std::vector<std::string>& candidates);

}  // namespace artcam::cli
