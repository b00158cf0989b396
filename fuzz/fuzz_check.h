// SPDX-License-Identifier: Apache-2.0
// What every fuzz target checks beyond "no crash, no hang, no huge allocation" (which libFuzzer
// and the sanitizers watch): a refusal is ONE line that starts with the name the reader was
// given, so a user sees which file is bad (README, "Errors"). A violation aborts, which
// libFuzzer records as a finding like any crash.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace artcam::fuzz {

// The name the targets hand to the readers; messages must start with it.
inline constexpr char kInputName[] = "fuzz-input";

inline void checkRefusal(const std::string& message, std::string_view name = kInputName) {
  const bool names_file = message.compare(0, name.size(), name) == 0;
  const bool has_cause = message.size() > name.size() + 2;
  const bool one_line = message.find('\n') == std::string::npos;
  if (names_file && has_cause && one_line) return;
  std::fprintf(stderr, "bad refusal message (must be one line starting with \"%.*s\"): \"%s\"\n",
               static_cast<int>(name.size()), name.data(), message.c_str());
  std::abort();
}

inline void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz check failed: %s\n", what);
  std::abort();
}

inline std::string_view textOf(const unsigned char* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace artcam::fuzz
