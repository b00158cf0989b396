// SPDX-License-Identifier: Apache-2.0
#include "core/io/standard_streams.h"

#include "core/io/io_text.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace artcam {

namespace {

std::string temporaryFolder() {
  const char* tmp = std::getenv("TMPDIR");
  return tmp && *tmp ? tmp : "/tmp";
}

// Writes all of `size` bytes or fails with errno set.
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// An unnamed file for the spool: O_TMPFILE, else a named one unlinked at once.
int anonymousFile() {
  const std::string folder = temporaryFolder();
  int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
  std::string name = folder + "/.artcam-stdin-XXXXXX";
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  fd = ::mkostemp(buffer.data(), O_CLOEXEC);
  if (fd >= 0) ::unlink(buffer.data());
  return fd;
}

bool g_stdout_closed_at_start = false;
// The descriptor data for standard output goes to: 1 unless reserveStandardOutputForData ran.
int g_data_fd = STDOUT_FILENO;

}  // namespace

void guardStandardDescriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // The lowest free descriptor is `fd` itself (those below it are open by now).
    const int opened = ::open("/dev/null", (fd == 0 ? O_WRONLY : O_RDONLY));
    if (opened >= 0 && opened != fd) {
      ::dup2(opened, fd);
      ::close(opened);
    }
    if (fd == STDOUT_FILENO) g_stdout_closed_at_start = true;
  }
}

bool standardOutputWasClosed() { return g_stdout_closed_at_start; }

void reserveStandardOutputForData() {
  if (g_data_fd != STDOUT_FILENO) return;
  std::fflush(stdout);
  const int data = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
  if (data < 0) return;  // the data then shares descriptor 1, as without the reservation
  if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    ::close(data);
    return;
  }
  g_data_fd = data;
}

Status writeStandardOutputData(const std::string& bytes) {
  const std::string fail = kStdoutName + ": cannot write: ";
  if (g_stdout_closed_at_start) return Status::failure(fail + "standard output is closed");
  std::fflush(stdout);
  // A reader that closes the pipe early (`| head -c 10`) would kill the process by SIGPIPE with
  // no word; ignored for this write, the write fails with EPIPE and the command says so.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  const bool ignoring = sigaction(SIGPIPE, &ignore, &previous) == 0;
  const bool written = writeAll(g_data_fd, bytes.data(), bytes.size());
  const int write_errno = errno;
  if (ignoring) sigaction(SIGPIPE, &previous, nullptr);
  if (!written)
    return Status::failure(fail + (write_errno == EPIPE
                                       ? std::string("the reader closed the pipe before all "
                                                     "was written")
                                       : std::string(std::strerror(write_errno))));
  return Status::success();
}

Status finishStandardOutput() {
  const std::string fail = kStdoutName + ": cannot write: ";
  // stdio keeps what it could not write and tries again here, so the flush names the cause.
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int flush_errno = errno;
  if (flushed && !std::ferror(stdout)) {
    errno = 0;
    if (std::fclose(stdout) != 0 && errno != EBADF)
      return Status::failure(fail + std::strerror(errno));
    return Status::success();
  }
  if (g_stdout_closed_at_start) return Status::failure(fail + "standard output is closed");
  return Status::failure(
      fail + (flush_errno != 0 ? std::strerror(flush_errno) : "an earlier write to it failed"));
}

StdinSpool::StdinSpool(int fd, std::size_t bytes)
    : fd_(fd), bytes_(bytes), path_("/proc/self/fd/" + std::to_string(fd)) {}

StdinSpool::~StdinSpool() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::shared_ptr<const StdinSpool>> StdinSpool::read() {
  using R = Result<std::shared_ptr<const StdinSpool>>;
  const std::string fail = kStdinName + ": cannot read: ";
  // A terminal would wait for typed bytes that never make an image: refused, not waited on.
  if (::isatty(STDIN_FILENO) == 1)
    return R::failure(fail + "standard input is a terminal; pipe an image into it");
  const int fd = anonymousFile();
  if (fd < 0)
    return R::failure(fail + "cannot make a temporary file in " + temporaryFolder() + ": " +
                      std::strerror(errno));
  std::shared_ptr<StdinSpool> spool(new StdinSpool(fd, 0));
  std::vector<char> chunk(1 << 20);
  for (;;) {
    const ssize_t n = ::read(STDIN_FILENO, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return R::failure(fail + std::strerror(errno));
    if (n == 0) break;
    if (!writeAll(fd, chunk.data(), static_cast<std::size_t>(n)))
      return R::failure(fail + "cannot spool it to " + temporaryFolder() + ": " +
                        std::strerror(errno));
    spool->bytes_ += static_cast<std::size_t>(n);
  }
  if (spool->bytes_ == 0) return R::failure(fail + "standard input is empty");
  return R::success(std::move(spool));
}

std::string StdinSpool::named(std::string message) const {
  return io_text::replaceAll(std::move(message), path_, kStdinName);
}

StdoutSpool::StdoutSpool(std::string folder, std::string path)
    : folder_(std::move(folder)), path_(std::move(path)) {}

StdoutSpool::~StdoutSpool() {
  std::error_code error;
  std::filesystem::remove_all(folder_, error);
}

Result<std::shared_ptr<StdoutSpool>> StdoutSpool::create(const std::string& extension) {
  using R = Result<std::shared_ptr<StdoutSpool>>;
  std::string name = temporaryFolder() + "/artcam-stdout-XXXXXX";
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  if (!::mkdtemp(buffer.data()))
    return R::failure(kStdoutName + ": cannot write: cannot make a temporary folder in " +
                      temporaryFolder() + ": " + std::strerror(errno));
  std::string folder(buffer.data());
  std::string path = folder + "/stdout." + extension;
  return R::success(std::shared_ptr<StdoutSpool>(new StdoutSpool(folder, path)));
}

Status StdoutSpool::send() const {
  const std::string fail = kStdoutName + ": cannot write: ";
  std::FILE* in = std::fopen(path_.c_str(), "rb");
  if (!in) return Status::failure(fail + "the encoded image is missing");
  std::vector<char> bytes;
  std::vector<char> chunk(1 << 20);
  for (std::size_t n; (n = std::fread(chunk.data(), 1, chunk.size(), in)) > 0;)
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
  const bool read_ok = !std::ferror(in);
  std::fclose(in);
  if (!read_ok) return Status::failure(fail + "cannot read back the encoded image");
  // Nothing else of ours is on standard output (the commands report on stderr), so the raw
  // descriptor carries exactly the image.
  const Status sent = writeStandardOutputData(std::string(bytes.begin(), bytes.end()));
  if (!sent && sent.message.find("closed the pipe") != std::string::npos)
    return Status::failure(fail + "the reader closed the pipe before the whole image was written");
  return sent;
}

std::string StdoutSpool::named(std::string message) const {
  message = io_text::replaceAll(std::move(message), path_, kStdoutName);
  return io_text::replaceAll(std::move(message), folder_, kStdoutName);
}

}  // namespace artcam
