// Atomic saves: POSIX rename(2) within one folder replaces the target in one step, so a reader
// sees either the old file or the complete new one, never a partial write. The temporary keeps
// the target's extension because image writers pick their format from it.
#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace artcam {

namespace {

std::string errnoText(int err) { return std::strerror(err); }

// ".name.tmp-<pid>-<n>.ext" beside the target: hidden, unique per process and call, and with
// the target's extension.
std::string temporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path target(path);
  const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                           "-" + std::to_string(counter++) + target.extension().string();
  return (target.parent_path() / name).string();
}

// fsync a file (or folder) by path; the data must be on disk before the rename makes it visible.
bool syncPath(const std::string& path, int flags, int& err) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) {
    err = errno;
    return false;
  }
  const bool ok = ::fsync(fd) == 0;
  if (!ok) err = errno;
  ::close(fd);
  return ok;
}

}  // namespace

Status writeAtomically(const std::string& path,
                       const std::function<Status(const std::string& temp_path)>& write) {
  if (path.empty()) return Status::failure("cannot write: empty file name");
  const std::string temp = temporaryPathFor(path);
  auto discard = [&] {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
  };

  Status written;
  try {
    written = write(temp);
  } catch (...) {
    discard();
    throw;
  }
  if (!written) {
    discard();
    return written;
  }
  std::error_code exists_error;
  if (!std::filesystem::exists(temp, exists_error)) {
    return Status::failure(path + ": cannot write: the writer produced no file");
  }

  int err = 0;
  if (!syncPath(temp, O_RDONLY, err)) {
    discard();
    return Status::failure(path + ": cannot write: " + errnoText(err));
  }
  // Keep the permissions of the file being replaced (a new file gets the umask default).
  struct stat old_stat {};
  if (::stat(path.c_str(), &old_stat) == 0) ::chmod(temp.c_str(), old_stat.st_mode & 07777);

  if (::rename(temp.c_str(), path.c_str()) != 0) {
    err = errno;
    discard();
    return Status::failure(path + ": cannot write: " + errnoText(err));
  }
  // Make the rename itself durable; failing here leaves a complete file, so it is not an error.
  std::string folder = std::filesystem::path(path).parent_path().string();
  if (folder.empty()) folder = ".";
  int ignored = 0;
  syncPath(folder, O_RDONLY | O_DIRECTORY, ignored);
  return Status::success();
}

Status writeTextAtomically(const std::string& path, const std::string& text) {
  return writeAtomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return Status::failure(path + ": cannot write: " + errnoText(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) return Status::failure(path + ": cannot write: " + errnoText(errno));
    return Status::success();
  });
}

}  // namespace artcam
