// SPDX-License-Identifier: Apache-2.0
#include "app/cli/terminal_text.h"

#include <unistd.h>
#include <cerrno>
#include <cstdio>

namespace artcam::cli {
namespace {

void appendHex(std::string& out, const char* prefix, unsigned value, int digits) {
  static const char kHex[] = "0123456789abcdef";
  out += prefix;
  for (int shift = 4 * (digits - 1); shift >= 0; shift -= 4) out += kHex[(value >> shift) & 15];
}

// Escapes `text` into `out`; `pending_lead` carries a 0xC2 byte split from its continuation by a
// buffer boundary (the lead byte of U+0080..U+00BF, among them the C1 controls).
void escapeInto(std::string& out, std::string_view text, bool& pending_lead) {
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (pending_lead) {
      pending_lead = false;
      if (byte >= 0x80 && byte <= 0x9f) {
        appendHex(out, "\\u", byte, 4);
        continue;
      }
      out += '\xc2';
    }
    if (byte == 0xc2) {
      pending_lead = true;
    } else if (byte == '\n' || byte == '\t') {
      out += ch;
    } else if (byte == '\r') {
      out += "\\r";
    } else if (byte < 0x20 || byte == 0x7f) {
      appendHex(out, "\\x", byte, 2);
    } else {
      out += ch;
    }
  }
}

struct FilteredStream {
  int fd = -1;
  bool pending_lead = false;
};

bool writeAll(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

ssize_t filteredWrite(void* cookie, const char* data, size_t size) {
  auto* stream = static_cast<FilteredStream*>(cookie);
  std::string out;
  out.reserve(size + 16);
  escapeInto(out, std::string_view(data, size), stream->pending_lead);
  // stdio counts what it handed over; the escapes are ours to write in full.
  return writeAll(stream->fd, out.data(), out.size()) ? static_cast<ssize_t>(size) : -1;
}

int filteredClose(void* cookie) {
  auto* stream = static_cast<FilteredStream*>(cookie);
  if (stream->pending_lead) writeAll(stream->fd, "\xc2", 1);
  stream->pending_lead = false;
  return 0;  // the descriptor stays open: the original stream still names it
}

std::FILE* g_raw_stderr = stderr;

std::FILE* filtered(int fd, int buffering) {
  static FilteredStream streams[3];
  streams[fd].fd = fd;
  cookie_io_functions_t functions{};
  functions.write = filteredWrite;
  functions.close = filteredClose;
  std::FILE* file = ::fopencookie(&streams[fd], "w", functions);
  if (file) std::setvbuf(file, nullptr, buffering, buffering == _IONBF ? 0 : BUFSIZ);
  return file;
}

}  // namespace

std::string terminalSafe(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  bool pending_lead = false;
  escapeInto(out, text, pending_lead);
  if (pending_lead) out += '\xc2';
  return out;
}

void guardTerminalStreams() {
  g_raw_stderr = stderr;
  if (::isatty(STDOUT_FILENO) == 1) {
    std::fflush(stdout);
    if (std::FILE* file = filtered(STDOUT_FILENO, _IOLBF)) stdout = file;
  }
  if (::isatty(STDERR_FILENO) == 1) {
    std::fflush(stderr);
    if (std::FILE* file = filtered(STDERR_FILENO, _IONBF)) stderr = file;
  }
}

std::FILE* terminalControlStream() { return g_raw_stderr; }

}  // namespace artcam::cli
