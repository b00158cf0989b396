// SPDX-License-Identifier: Apache-2.0
#include "app/cli/args.h"

#include <algorithm>
#include <charconv>
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
  const auto parse = [](const std::string& s, int& out) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && out > 0 && out <= 1000000;
  };
  if (x == std::string::npos || !parse(text.substr(0, x), size.width) ||
      !parse(text.substr(x + 1), size.height))
    throw UsageError(option + " expects WxH in pixels (1…1000000), got \"" + text + "\"");
  return size;
}

namespace {

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
