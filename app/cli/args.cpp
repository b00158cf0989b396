#include "app/cli/args.h"

#include <charconv>

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
    if (!spec) throw UsageError("unknown option " + name);
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

FrameSize parseSize(const std::string& text, const std::string& option) {
  const size_t x = text.find_first_of("xX");
  FrameSize size;
  const auto parse = [](const std::string& s, int& out) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && out > 0 && out <= 1000000;
  };
  if (x == std::string::npos || !parse(text.substr(0, x), size.width) ||
      !parse(text.substr(x + 1), size.height))
    throw UsageError(option + " expects WIDTHxHEIGHT in pixels (1…1000000), got \"" + text + "\"");
  return size;
}

}  // namespace artcam::cli
