// SPDX-License-Identifier: Apache-2.0
#include "core/io/text_input.h"

#include "core/io/image_checks.h"
#include "core/io/standard_streams.h"
#include "core/util/memory_budget.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace artcam {
namespace {

// Reads `fd` to its end into `text`, failing once it holds more than `cap` bytes (so a file
// that grows while read, or a pipe, cannot pass the cap either).
Status readAll(int fd, std::size_t cap, std::string& text, const std::string& fail) {
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Status::failure(fail + std::strerror(errno));
    if (n == 0) return Status::success();
    if (text.size() + static_cast<std::size_t>(n) > cap)
      return Status::failure(fail + "larger than the " + describeBytes(static_cast<double>(cap)) +
                             " a text input may hold");
    text.append(chunk, static_cast<std::size_t>(n));
  }
}

}  // namespace

std::string textInputName(const std::string& path) { return path == "-" ? kStdinName : path; }

Result<std::string> readTextInput(const std::string& path, const TextInputOptions& options) {
  using R = Result<std::string>;
  const std::string fail = textInputName(path) + ": cannot read: ";
  std::string text;
  if (path == "-") {
    if (::isatty(STDIN_FILENO) == 1)
      return R::failure(fail + "standard input is a terminal; pipe the file into it");
    if (const Status read = readAll(STDIN_FILENO, options.max_bytes, text, fail); !read)
      return R::failure(read.message);
    return R::success(std::move(text));
  }
  // O_NONBLOCK: opening a named pipe without a writer returns at once (and is then refused)
  // instead of waiting for one.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    return R::failure(
        fail + (errno == ENOENT ? std::string("no such file") : std::string(std::strerror(errno))));
  struct stat st {};
  Status status = Status::success();
  if (::fstat(fd, &st) != 0) {
    status = Status::failure(fail + std::strerror(errno));
  } else if (!S_ISREG(st.st_mode)) {
    status = Status::failure(fail + image_checks::notRegularFile(st.st_mode));
  } else if (static_cast<unsigned long long>(st.st_size) > options.max_bytes) {
    status = Status::failure(
        fail + describeBytes(static_cast<double>(st.st_size)) + ", more than the " +
        describeBytes(static_cast<double>(options.max_bytes)) + " a text input may hold");
  } else {
    // A regular file reads whole; O_NONBLOCK means nothing for it.
    text.reserve(static_cast<std::size_t>(st.st_size));
    status = readAll(fd, options.max_bytes, text, fail);
  }
  ::close(fd);
  if (!status) return R::failure(status.message);
  return R::success(std::move(text));
}

}  // namespace artcam
