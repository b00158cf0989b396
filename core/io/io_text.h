// SPDX-License-Identifier: Apache-2.0
// Small text helpers shared by core's file readers (io, project); not part of the engine's API.
// A Status message is one line (status.h), so multi-line library messages are folded.
#pragma once

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>

namespace artcam::io_text {

inline std::string oneLine(std::string message) {
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at))
    message.replace(at, 1, "; ");
  return message.empty() ? "unknown error" : message;
}

// The cause of a decoder's exception in a user's words. The standard library's own texts
// ("vector::_M_default_append", "std::bad_alloc") say nothing to a user and never reach one: a
// length error is a size in the file beyond any image, an allocation failure is memory.
inline std::string decoderFailure(const std::exception& e) {
  if (dynamic_cast<const std::length_error*>(&e))
    return "the decoder failed: the file claims a size beyond any image (a corrupt header)";
  if (dynamic_cast<const std::bad_alloc*>(&e)) return "not enough memory to decode it";
  return "the decoder failed: " + oneLine(e.what());
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

// The byte offset where JSON text nests deeper than `max_depth` brackets, or npos. Brackets
// inside strings do not count. Readers refuse such text before parsing it: re-serialising parts
// of a deep tree recurses, and a few hundred kilobytes of "[[[[" would overflow the stack.
inline size_t jsonTooDeepAt(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return k;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string_view::npos;
}

// "line L, column C" of a byte of `text` (1-based, counted in bytes), as parsers report it.
inline std::string jsonPositionOf(std::string_view text, size_t byte) {
  const size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  size_t line = 1, line_start = 0;
  for (size_t k = 0; k < end; ++k)
    if (text[k] == '\n') ++line, line_start = k + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(end - line_start + 1);
}

}  // namespace artcam::io_text
