// SPDX-License-Identifier: Apache-2.0
#include "app/cli/args.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace artcam::cli {

Args::Args(const std::vector<std::string>& argv, const std::vector<OptionSpec>& specs) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() < 2 || a[0] != '-' || a == "--") {
      positional_.push_back(a == "--" && i + 1 < argv.size() ? argv[++i] : a);
      continue;
    }
    std::string name = a, inline_value;
    bool has_inline = false;
    if (const size_t eq = a.find('='); a.rfind("--", 0) == 0 && eq != std::string::npos) {
      name = a.substr(0, eq);
      inline_value = a.substr(eq + 1);
      has_inline = true;
    }
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& s : specs)
      if (s.name == name || (!s.short_name.empty() && s.short_name == name)) spec = &s;
    if (!spec) {
      std::vector<std::string> known;
      for (const OptionSpec& s : specs) known.push_back(s.name);
      throw UsageError("unknown option " + name, didYouMean(name, known));
    }
    if (!spec->takes_value) {
      if (has_inline) throw UsageError(spec->name + " takes no value");
      values_[spec->name] = "";
    } else if (has_inline) {
      values_[spec->name] = inline_value;
    } else {
      if (i + 1 >= argv.size()) throw UsageError(spec->name + " needs a value");
      values_[spec->name] = argv[++i];
    }
  }
}

std::optional<std::string> Args::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Args::valueOr(const std::string& name, const std::string& fallback) const {
  return value(name).value_or(fallback);
}

void Args::expectPositional(size_t count, const std::string& what) const {
  if (positional_.size() < count) throw UsageError("missing " + what);
  if (positional_.size() > count) throw UsageError("unexpected argument " + positional_[count]);
}

FrameSize parseSize(const std::string& text, const std::string& option, bool legacy_comma) {
  const size_t x = text.find_first_of(legacy_comma ? "xX," : "xX");
  FrameSize size;
  const auto parse = [](std::string_view s, int& out) {
    const auto v = readInteger(s);
    if (!v || *v <= 0 || *v > 1000000) return false;
    out = static_cast<int>(*v);
    return true;
  };
  const std::string_view whole(text);
  if (x == std::string::npos || !parse(whole.substr(0, x), size.width) ||
      !parse(whole.substr(x + 1), size.height))
    throw UsageError(option + " expects WxH in pixels (1…1000000), got \"" + text + "\"");
  return size;
}

FrameSize parseSizeByAspect(const std::string& text, const std::string& option) {
  const size_t x = text.find_first_of("xX");
  const std::string_view whole(text);
  const bool zero_width = x != std::string::npos && whole.substr(0, x) == "0";
  const bool zero_height = x != std::string::npos && whole.substr(x + 1) == "0";
  if (zero_width && zero_height)
    throw UsageError(option + " expects WxH with at most one side 0 (by aspect), got \"" + text +
                     "\"");
  if (!zero_width && !zero_height) return parseSize(text, option);
  const auto given = readInteger(zero_width ? whole.substr(x + 1) : whole.substr(0, x));
  if (!given || *given <= 0 || *given > 1000000)
    throw UsageError(option + " expects WxH in pixels (1…1000000; one side 0: by aspect), got \"" +
                     text + "\"");
  FrameSize size;
  (zero_width ? size.height : size.width) = static_cast<int>(*given);
  return size;
}

namespace {

// An end of a range as users read it: whole values without a decimal point or exponent.
std::string endText(double v) {
  char buf[32];
  if (v == std::floor(v) && std::abs(v) < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "from 0 to 1024", "above 0, below 180", "of at least 0", "" (no bound).
std::string rangeText(double min, double max, Ends ends) {
  const bool open_min = ends == Ends::OpenMin || ends == Ends::Open;
  const bool open_max = ends == Ends::OpenMax || ends == Ends::Open;
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max && !open_min && !open_max)
    return "from " + endText(min) + " to " + endText(max);
  std::string text;
  if (has_min) text = (open_min ? "above " : "of at least ") + endText(min);
  if (has_max)
    text += (text.empty() ? (open_max ? "below " : "of at most ")
                          : (open_max ? ", below " : ", at most ")) +
            endText(max);
  return text;
}

[[noreturn]] void refuse(const std::string& option, const std::string& kind, double min, double max,
                         Ends ends, std::string_view text) {
  const std::string range = rangeText(min, max, ends);
  throw UsageError(option + " expects " + kind + (range.empty() ? "" : " " + range) + ", got \"" +
                   std::string(text) + "\"");
}

bool inRange(double v, double min, double max, Ends ends) {
  const bool open_min = ends == Ends::OpenMin || ends == Ends::Open;
  const bool open_max = ends == Ends::OpenMax || ends == Ends::Open;
  return (open_min ? v > min : v >= min) && (open_max ? v < max : v <= max);
}

std::vector<std::string_view> commaItems(std::string_view text) {
  std::vector<std::string_view> items;
  for (size_t start = 0;;) {
    const size_t comma = text.find(',', start);
    items.push_back(
        text.substr(start, comma == std::string_view::npos ? text.npos : comma - start));
    if (comma == std::string_view::npos) return items;
    start = comma + 1;
  }
}

std::string_view withoutDashes(std::string_view s) {
  while (!s.empty() && s.front() == '-') s.remove_prefix(1);
  return s;
}

// Optimal string alignment distance: insertions, deletions, substitutions and transpositions
// of neighbours ("filtr" → "filter" 1, "fitler" → "filter" 1).
size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::optional<long long> readInteger(std::string_view text) {
  long long v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size())
    return std::nullopt;
  return v;
}

std::optional<double> readNumber(std::string_view text) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() ||
      !std::isfinite(v))
    return std::nullopt;
  return v;
}

long long parseInteger(std::string_view text, const std::string& option, long long min,
                       long long max) {
  const auto v = readInteger(text);
  if (!v || *v < min || *v > max)
    refuse(option, "a whole number", static_cast<double>(min), static_cast<double>(max),
           Ends::Closed, text);
  return *v;
}

double parseNumber(std::string_view text, const std::string& option, double min, double max,
                   Ends ends) {
  const auto v = readNumber(text);
  if (!v || !inRange(*v, min, max, ends)) refuse(option, "a number", min, max, ends, text);
  return *v;
}

std::vector<long long> parseIntegerList(std::string_view text, const std::string& option,
                                        long long min, long long max) {
  std::vector<long long> out;
  for (const std::string_view item : commaItems(text)) {
    const auto v = readInteger(item);
    if (!v || *v < min || *v > max)
      refuse(option, "comma-separated whole numbers", static_cast<double>(min),
             static_cast<double>(max), Ends::Closed, text);
    out.push_back(*v);
  }
  return out;
}

std::vector<double> parseNumberList(std::string_view text, const std::string& option, double min,
                                    double max, Ends ends) {
  std::vector<double> out;
  for (const std::string_view item : commaItems(text)) {
    const auto v = readNumber(item);
    if (!v || !inRange(*v, min, max, ends))
      refuse(option, "comma-separated numbers", min, max, ends, text);
    out.push_back(*v);
  }
  return out;
}

int intOption(const Args& args, const std::string& option, int fallback, int min, int max) {
  const auto text = args.value(option);
  return text ? static_cast<int>(parseInteger(*text, option, min, max)) : fallback;
}

double numberOption(const Args& args, const std::string& option, double fallback, double min,
                    double max, Ends ends) {
  const auto text = args.value(option);
  return text ? parseNumber(*text, option, min, max, ends) : fallback;
}

std::string closestName(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string_view word = withoutDashes(typed);
  if (word.empty()) return {};
  for (const std::string& c : candidates)
    if (withoutDashes(c) == word) return c;
  std::vector<const std::string*> prefixed;
  for (const std::string& c : candidates)
    if (withoutDashes(c).starts_with(word)) prefixed.push_back(&c);
  if (prefixed.size() == 1) return *prefixed.front();
  if (prefixed.size() > 1) return {};
  size_t best = 3;  // more than the largest distance a hint allows
  const std::string* found = nullptr;
  bool tie = false;
  for (const std::string& c : candidates) {
    const size_t d = editDistance(word, withoutDashes(c));
    if (d < best) {
      best = d;
      found = &c;
      tie = false;
    } else if (d == best) {
      tie = true;
    }
  }
  // A one-letter word is within distance 1 of every one-letter name: no hint from that.
  if (!found || tie || best >= word.size()) return {};
  return *found;
}

std::string didYouMean(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string name = closestName(typed, candidates);
  return name.empty() ? std::string() : "did you mean " + name + "?";
}

}  // namespace artcam::cli
