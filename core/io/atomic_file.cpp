// SPDX-License-Identifier: Apache-2.0
// Atomic saves: POSIX rename(2) within one folder replaces the target in one step, so a reader
// sees either the old file or the complete new one, never a partial write. The temporary keeps
// the target's extension because image writers pick their format from it.
#include "core/io/atomic_file.h"

#include "core/io/standard_streams.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>

namespace artcam {

namespace {

std::string errnoText(int err) { return std::strerror(err); }

std::string temporaryPrefixFor(const std::filesystem::path& target) {
  return "." + target.stem().string() + ".tmp-";
}

// ".name.tmp-<pid>-<n>.ext" beside the target: hidden, unique per process and call, and with
// the target's extension.
std::string temporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path target(path);
  const std::string name = temporaryPrefixFor(target) + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + target.extension().string();
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

// The live temporaries, readable from a signal handler: fixed slots, no allocation. A slot's
// state is generation·4 + {0 free, 1 being filled, 2 live}; the handler copies a live path and
// unlinks it only if the state did not change meanwhile (another thread may reuse the slot).
constexpr int kLiveSlots = 64;
constexpr std::size_t kMaxLivePath = 4096;
struct LiveSlot {
  std::atomic<unsigned long> state{0};
  char path[kMaxLivePath];
};
static_assert(std::atomic<unsigned long>::is_always_lock_free);
LiveSlot g_live[kLiveSlots];

// Returns the slot, or -1 when the path is too long or all slots are taken (the save still
// works; only the signal-time cleanup misses it).
int registerLive(const std::string& path) {
  if (path.size() >= kMaxLivePath) return -1;
  for (int i = 0; i < kLiveSlots; ++i) {
    unsigned long state = g_live[i].state.load();
    if ((state & 3) != 0 || !g_live[i].state.compare_exchange_strong(state, state + 1)) continue;
    std::memcpy(g_live[i].path, path.c_str(), path.size() + 1);
    g_live[i].state.store(state + 2, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregisterLive(int slot) {
  if (slot < 0) return;
  const unsigned long state = g_live[slot].state.load();
  g_live[slot].state.store((state & ~3UL) + 4, std::memory_order_release);
}

// "<pid>-<n>" → pid, or -1.
long pidOfTemporary(const std::string& middle) {
  const size_t dash = middle.find('-');
  if (dash == 0 || dash == std::string::npos || dash + 1 == middle.size()) return -1;
  for (size_t k = 0; k < middle.size(); ++k)
    if (k != dash && (middle[k] < '0' || middle[k] > '9')) return -1;
  try {
    return std::stol(middle.substr(0, dash));
  } catch (const std::exception&) {
    return -1;
  }
}

// The targets commitWithoutReplacing marked, as absolute normal paths.
std::mutex g_no_replace_mutex;
std::set<std::string> g_no_replace;

std::string markKey(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  return (ec ? std::filesystem::path(path) : absolute).lexically_normal().string();
}

// Takes (and clears) the mark of `path`.
bool takeNoReplaceMark(const std::string& path) {
  const std::lock_guard<std::mutex> lock(g_no_replace_mutex);
  return g_no_replace.erase(markKey(path)) > 0;
}

// Moves `temp` to `path` only if no file has that name: renameat2's RENAME_NOREPLACE, else
// (a file system without it) a hard link then unlinking the temporary. 0 or an errno (EEXIST:
// the name was taken meanwhile).
int commitNoReplace(const std::string& temp, const std::string& path) {
  if (::renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, path.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) return errno;
  if (::link(temp.c_str(), path.c_str()) != 0) return errno;
  ::unlink(temp.c_str());
  return 0;
}

}  // namespace

void commitWithoutReplacing(const std::string& path) {
  const std::lock_guard<std::mutex> lock(g_no_replace_mutex);
  g_no_replace.insert(markKey(path));
}

void removeLiveTemporaries() noexcept {
  for (LiveSlot& slot : g_live) {
    const unsigned long before = slot.state.load(std::memory_order_acquire);
    if ((before & 3) != 2) continue;
    char copy[kMaxLivePath];
    std::memcpy(copy, slot.path, kMaxLivePath);
    copy[kMaxLivePath - 1] = '\0';
    if (slot.state.load(std::memory_order_acquire) == before) ::unlink(copy);
  }
}

bool isAtomicTemporaryName(const std::string& file_name) {
  static const std::regex kName(R"(^\..*\.tmp-[0-9]+-[0-9]+(\.[^.]*)?$)");
  return std::regex_match(file_name, kName);
}

int removeStaleTemporaries(const std::string& path) {
  const std::filesystem::path target(path);
  const std::string prefix = temporaryPrefixFor(target);
  const std::string extension = target.extension().string();
  std::filesystem::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  int removed = 0;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const long pid =
        pidOfTemporary(name.substr(prefix.size(), name.size() - prefix.size() - extension.size()));
    // Only a writer that is gone: kill(pid, 0) fails with ESRCH. A live one (ours, another
    // process's, or one we may not signal) keeps its file.
    if (pid <= 0 || pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
      continue;
    std::error_code ignored;
    if (std::filesystem::remove(it->path(), ignored)) ++removed;
  }
  return removed;
}

Status writeAtomically(const std::string& path,
                       const std::function<Status(const std::string& temp_path)>& write) {
  if (path.empty()) return Status::failure("cannot write: empty file name");
  // "-": standard output. The writer writes a private spool file, sent only once it succeeded,
  // so a failed write puts nothing on the stream (standard_streams.h).
  if (path == "-") {
    auto spool = StdoutSpool::create("data");
    if (!spool) return spool.status;
    const Status written = write((*spool)->path());
    if (!written) return Status::failure((*spool)->named(written.message));
    return (*spool)->send();
  }
  removeStaleTemporaries(path);
  const std::string temp = temporaryPathFor(path);
  // Registered before the writer creates it, so a signal at any point finds it.
  const int slot = registerLive(temp);
  auto discard = [&] {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    unregisterLive(slot);
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
    unregisterLive(slot);
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

  const bool no_replace = takeNoReplaceMark(path);
  err = no_replace                                  ? commitNoReplace(temp, path)
        : ::rename(temp.c_str(), path.c_str()) == 0 ? 0
                                                    : errno;
  if (err != 0) {
    discard();
    if (no_replace) commitWithoutReplacing(path);  // still not ours to replace
    return Status::failure(path + (err == EEXIST && no_replace
                                       ? " appeared while it was being written (another program "
                                         "wrote it); pass --overwrite to replace it"
                                       : ": cannot write: " + errnoText(err)));
  }
  unregisterLive(slot);
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
