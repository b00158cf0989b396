// SPDX-License-Identifier: Apache-2.0
// Small text helpers shared by the io room's .cpp files (not part of the engine's API).
// A Status message is one line (status.h), so multi-line library messages are folded.
#pragma once

#include <string>

namespace artcam::io_text {

inline std::string oneLine(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at))
    message.replace(at, 1, "; ");
  return message.empty() ? "unknown error" : message;
}

inline std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c);
  return s;
}

inline bool isIntegerPixelType(const std::string& type) {
  return type == "uint8" || type == "uint16";
}

}  // namespace artcam::io_text
