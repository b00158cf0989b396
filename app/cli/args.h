// A small command-line parser: positional arguments and --options (with or without a value).
// Usage errors throw UsageError, which the dispatcher prints with the subcommand's usage.
#pragma once

#include "core/model/camera.h"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace artcam::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
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

// "WxH" → frame size; throws UsageError naming the option.
FrameSize parseSize(const std::string& text, const std::string& option);

}  // namespace artcam::cli
