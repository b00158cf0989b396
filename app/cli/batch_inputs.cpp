// SPDX-License-Identifier: Apache-2.0
#include "app/cli/batch_inputs.h"

#include "app/cli/args.h"
#include "app/cli/commands.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
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

// A frame number of a list, as written: digits only, within kMaxFrameNumber.
long listedFrame(const std::string& text, const std::string& whole, const std::string& option) {
  const auto n = readInteger(text);
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || !n ||
      *n > kMaxFrameNumber)
    throw UsageError(option + " \"" + whole +
                     "\": expected frames such as 1001-1100, 1001-1100x2 or 1001,1005,1010-1020 "
                     "(numbers from 0 to " +
                     std::to_string(kMaxFrameNumber) + ")");
  return static_cast<long>(*n);
}

}  // namespace

std::vector<long> parseFrameList(const std::string& text, const std::string& option) {
  std::vector<long> frames;
  std::set<long> seen;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    start = comma + 1;
    const size_t dash = part.find('-');
    const size_t times = part.find('x');
    const long from = listedFrame(part.substr(0, std::min(dash, times)), text, option);
    long to = from, step = 1;
    if (dash != std::string::npos) {
      to = listedFrame(
          part.substr(dash + 1, times == std::string::npos || times < dash ? std::string::npos
                                                                           : times - dash - 1),
          text, option);
      if (times != std::string::npos && times > dash)
        step = listedFrame(part.substr(times + 1), text, option);
    } else if (times != std::string::npos) {
      listedFrame("", text, option);  // "1001x2" without a range: refused
    }
    if (times != std::string::npos && dash != std::string::npos && times < dash)
      listedFrame("", text, option);  // "10x2-20": refused
    if (to < from)
      throw UsageError(option + " \"" + text + "\": the range " + part + " runs backwards");
    if (step < 1)
      throw UsageError(option + " \"" + text + "\": the step of " + part + " is not positive");
    for (long f = from; f <= to; f += step) {
      if (seen.insert(f).second) frames.push_back(f);
      if (frames.size() > kMaxListedFrames)
        throw UsageError(option + " \"" + text + "\": more than " +
                         std::to_string(kMaxListedFrames) + " frames");
    }
  }
  return frames;
}

BatchChunk parseChunk(const std::string& text, const std::string& option) {
  const size_t slash = text.find('/');
  const auto k = slash == std::string::npos ? std::nullopt : readInteger(text.substr(0, slash));
  const auto n = slash == std::string::npos ? std::nullopt : readInteger(text.substr(slash + 1));
  if (!k || !n || *n < 1 || *k < 1 || *k > *n || *n > static_cast<long long>(kMaxListedFrames))
    throw UsageError(option + " \"" + text +
                     "\": expected K/N, the K-th of N equal slices (1 <= K <= N), e.g. 2/4");
  return {static_cast<long>(*k), static_cast<long>(*n)};
}

std::pair<size_t, size_t> chunkRange(size_t total, const BatchChunk& chunk) {
  const auto edge = [&](long k) {
    return static_cast<size_t>(static_cast<unsigned long long>(total) *
                               static_cast<unsigned long long>(k) /
                               static_cast<unsigned long long>(chunk.count));
  };
  return {edge(chunk.index - 1), edge(chunk.index)};
}

std::vector<BatchInput> expandBatchInputs(const std::vector<std::string>& arguments,
                                          std::optional<long> first,
                                          const std::vector<long>* frames) {
  std::vector<BatchInput> inputs;
  for (const std::string& a : arguments) {
    std::error_code ec;
    // A file that exists is taken as named, even with a % in its name.
    const auto pattern =
        a.find('%') == std::string::npos || fs::exists(a, ec) ? std::nullopt : parsePattern(a);
    if (!pattern) {
      if (frames)
        throw UsageError("--frames picks frames of a pattern such as frames/f_%04d.exr; " + a +
                         " is not one");
      inputs.push_back(
          {fs::exists(a, ec) ? a : std::regex_replace(a, std::regex("%%"), "%"), std::nullopt});
      continue;
    }
    if (frames) {
      for (long f : *frames) inputs.push_back({frameName(*pattern, f), f});
      continue;
    }
    long n = first.value_or(fs::is_regular_file(frameName(*pattern, 0), ec) ? 0 : 1);
    const size_t before = inputs.size();
    for (; fs::is_regular_file(frameName(*pattern, n), ec); ++n)
      inputs.push_back({frameName(*pattern, n), n});
    if (inputs.size() == before)
      throw CommandError(a + ": no frame " + frameName(*pattern, first.value_or(1)) +
                         " to start from");
  }
  return inputs;
}

std::vector<BatchItem> planBatch(const std::vector<BatchInput>& inputs, const BatchNaming& naming) {
  std::vector<BatchItem> items;
  std::map<std::string, std::string> output_of;  // lexically normal output → its input
  for (const auto& [input, frame] : inputs) {
    const fs::path in(input);
    const std::string extension =
        naming.format.empty() ? in.extension().string() : "." + naming.format;
    const fs::path out = fs::path(naming.folder) / (in.stem().string() + naming.suffix + extension);
    const std::string key = fs::absolute(out).lexically_normal().string();
    if (const auto clash = output_of.find(key); clash != output_of.end())
      throw CommandError(out.string() + ": both " + clash->second + " and " + input +
                         " would be written there (use --suffix or --format, or separate runs)");
    output_of[key] = input;
    items.push_back({input, out.string(), frame});
  }
  return items;
}

}  // namespace artcam::cli
