// SPDX-License-Identifier: Apache-2.0
#include "app/cli/batch_inputs.h"

#include "app/cli/args.h"
#include "app/cli/commands.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <string_view>
#include <system_error>

namespace artcam::cli {
namespace {

namespace fs = std::filesystem;

struct Pattern {
  std::string before, after;
  size_t width = 0;  // zero padding
};

// The width of "%0Nd" from its flag and digits "0N" ("" and "0": none). Throws UsageError
// past kMaxFramePadding.
size_t padding(const std::string& pattern, const std::string& flag) {
  const std::string_view digits = std::string_view(flag).substr(std::min<size_t>(flag.size(), 1));
  if (digits.empty()) return 0;
  const auto width = readInteger(digits);
  if (!width || *width > kMaxFramePadding)
    throw UsageError("\"" + pattern + "\": a frame pattern pads to at most " +
                     std::to_string(kMaxFramePadding) + " digits (%0" +
                     std::to_string(kMaxFramePadding) + "d), got %" + flag + "d");
  return static_cast<size_t>(*width);
}

// Parsed by hand rather than handed to printf: the pattern comes from the user.
std::optional<Pattern> parsePattern(const std::string& text) {
  static const std::regex kNumber(R"(%(0[0-9]*)?d)");
  std::string literal;
  std::optional<Pattern> pattern;
  for (size_t k = 0; k < text.size(); ++k) {
    if (text[k] != '%') {
      literal += text[k];
      continue;
    }
    if (k + 1 < text.size() && text[k + 1] == '%') {
      literal += '%';
      ++k;
      continue;
    }
    std::smatch m;
    const std::string rest = text.substr(k);
    if (pattern || !std::regex_search(rest, m, kNumber, std::regex_constants::match_continuous))
      throw UsageError("\"" + text +
                       "\": a frame pattern takes one %d or %0Nd (%% for a literal %)");
    pattern = Pattern{literal, "", padding(text, m[1].str())};
    literal.clear();
    k += static_cast<size_t>(m.length(0)) - 1;
  }
  if (pattern) pattern->after = literal;
  return pattern;
}

std::string frameName(const Pattern& p, long number) {
  std::string digits = std::to_string(number);
  if (digits.size() < p.width) digits.insert(0, p.width - digits.size(), '0');
  return p.before + digits + p.after;
}

}  // namespace

std::vector<std::string> expandBatchInputs(const std::vector<std::string>& arguments,
                                           std::optional<long> first) {
  std::vector<std::string> inputs;
  for (const std::string& a : arguments) {
    std::error_code ec;
    // A file that exists is taken as named, even with a % in its name.
    const auto pattern =
        a.find('%') == std::string::npos || fs::exists(a, ec) ? std::nullopt : parsePattern(a);
    if (!pattern) {
      inputs.push_back(fs::exists(a, ec) ? a : std::regex_replace(a, std::regex("%%"), "%"));
      continue;
    }
    long n = first.value_or(fs::is_regular_file(frameName(*pattern, 0), ec) ? 0 : 1);
    const size_t before = inputs.size();
    for (; fs::is_regular_file(frameName(*pattern, n), ec); ++n)
      inputs.push_back(frameName(*pattern, n));
    if (inputs.size() == before)
      throw CommandError(a + ": no frame " + frameName(*pattern, first.value_or(1)) +
                         " to start from");
  }
  return inputs;
}

std::vector<BatchItem> planBatch(const std::vector<std::string>& inputs,
                                 const BatchNaming& naming) {
  std::vector<BatchItem> items;
  std::map<std::string, std::string> output_of;  // lexically normal output → its input
  for (const std::string& input : inputs) {
    const fs::path in(input);
    const std::string extension =
        naming.format.empty() ? in.extension().string() : "." + naming.format;
    const fs::path out = fs::path(naming.folder) / (in.stem().string() + naming.suffix + extension);
    const std::string key = fs::absolute(out).lexically_normal().string();
    if (const auto clash = output_of.find(key); clash != output_of.end())
      throw CommandError(out.string() + ": both " + clash->second + " and " + input +
                         " would be written there (use --suffix or --format, or separate runs)");
    output_of[key] = input;
    items.push_back({input, out.string()});
  }
  return items;
}

}  // namespace artcam::cli
