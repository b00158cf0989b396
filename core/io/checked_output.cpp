// SPDX-License-Identifier: Apache-2.0
#include "core/io/checked_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>
#include <vector>

namespace artcam::io_checked {

std::unique_ptr<CheckedOutput> CheckedOutput::create(const std::string& path) {
  // Read and write: a TIFF writer reads back what it wrote (its directories).
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return nullptr;
  return std::unique_ptr<CheckedOutput>(new CheckedOutput(fd, path));
}

CheckedOutput::CheckedOutput(int fd, const std::string& path)
    : IOProxy(path, IOProxy::Write), fd_(fd) {}

CheckedOutput::~CheckedOutput() {
  if (fd_ >= 0) ::close(fd_);
}

bool CheckedOutput::seek(int64_t offset) {
  if (offset < 0) return false;
  m_pos = offset;
  return true;
}

bool CheckedOutput::writeAt(const void* buf, size_t size, int64_t offset) {
  int64_t end = offset + static_cast<int64_t>(size);
  for (int64_t known = extent_.load(); end > known && !extent_.compare_exchange_weak(known, end);) {
  }
  if (first_error_.load() != 0) return false;  // the file is lost already: nothing more is written
  const char* data = static_cast<const char*>(buf);
  while (size > 0) {
    const ssize_t n = ::pwrite(fd_, data, size, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      int expected = 0;
      first_error_.compare_exchange_strong(expected, n < 0 ? errno : ENOSPC);
      return false;
    }
    data += n;
    size -= static_cast<size_t>(n);
    offset += n;
  }
  return true;
}

size_t CheckedOutput::write(const void* buf, size_t size) {
  writeAt(buf, size, m_pos);
  m_pos += static_cast<int64_t>(size);
  return size;  // even when it failed: firstError() fails the save, not the codec
}

size_t CheckedOutput::pwrite(const void* buf, size_t size, int64_t offset) {
  writeAt(buf, size, offset);
  return size;
}

size_t CheckedOutput::pread(void* buf, size_t size, int64_t offset) {
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd_, static_cast<char*>(buf) + done, size - done,
                              offset + static_cast<int64_t>(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  return done;
}

size_t CheckedOutput::read(void* buf, size_t size) {
  const size_t n = pread(buf, size, m_pos);
  m_pos += static_cast<int64_t>(n);
  return n;
}

size_t CheckedOutput::size() const { return static_cast<size_t>(extent_.load()); }

bool CheckedOutput::finish() {
  if (fd_ < 0) return first_error_.load() == 0;
  const int closed = ::close(fd_);
  fd_ = -1;
  int expected = 0;
  if (closed != 0) first_error_.compare_exchange_strong(expected, errno);
  return first_error_.load() == 0;
}

namespace {

// The formats whose writer takes a proxy and was seen to write through one the bytes it writes
// to a file of its own. Not TIFF: OpenImageIO 2.4's TIFF writer, given a proxy, writes a file
// whose first directory cannot be read back when there is an Exif directory beside it (libtiff
// checks its own writes, so TIFF is reported without the proxy).
bool takesCheckedOutput(const OIIO::ImageOutput& out) {
  static const std::set<std::string> kVerified{"png", "jpeg", "openexr", "hdr", "bmp",     "targa",
                                               "pnm", "webp", "gif",     "dpx", "jpeg2000"};
  return out.supports("ioproxy") && kVerified.count(out.format_name()) > 0;
}

}  // namespace

CheckedWrite::~CheckedWrite() {
  // The codec must be done with the proxy before the proxy goes.
  if (out_ && !closed_) {
    out_->close();
    out_->geterror();
  }
  out_.reset();
}

bool CheckedWrite::open(const std::string& temp, const OIIO::ImageSpec& spec) {
  return open(temp, std::vector<OIIO::ImageSpec>{spec});
}

bool CheckedWrite::open(const std::string& temp, const std::vector<OIIO::ImageSpec>& specs) {
  OIIO::ImageOutput& out = *out_;
  temp_ = temp;
  if (takesCheckedOutput(out)) {
    proxy_ = CheckedOutput::create(temp);
    if (!proxy_) {
      open_error_ = errno;
      return false;
    }
    if (!out.set_ioproxy(proxy_.get())) return false;
  } else {
    // The format opens the file itself and says only "could not open": the cause is asked of
    // the file system first.
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
      open_error_ = errno;
      return false;
    }
    ::close(fd);
  }
  return specs.size() == 1 ? out.open(temp, specs.front())
                           : out.open(temp, static_cast<int>(specs.size()), specs.data());
}

bool CheckedWrite::close() {
  closed_ = true;
  const bool closed = out_ && out_->close();
  if (proxy_ && out_) out_->set_ioproxy(nullptr);
  if (!closed) return false;
  if (proxy_) return proxy_->finish();
  // libtiff checks each of its writes, and OpenImageIO reports them (measured on a full disk).
  return out_->format_name() == std::string("tiff") || readsBack();
}

// A writer that opened the file itself may have lost bytes without a word (OpenImageIO 2.4's
// SGI writer on a full disk: "wrote", a file cut at the limit). The file is read back whole:
// the formats without a proxy are rare, and a save must not say "wrote" over a cut file.
bool CheckedWrite::readsBack() {
  // The writer's own format's reader: never a guess from the name (which could pick a reader
  // this program must not run, image_checks::movieContainer).
  auto in = OIIO::ImageInput::create(out_->format_name());
  OIIO::ImageSpec opened;
  const OIIO::ImageSpec& written = out_->spec();
  bool ok = in && in->open(temp_, opened) && in->spec().width == written.width &&
            in->spec().height == written.height;
  if (ok) {
    std::vector<unsigned char> pixels(in->spec().image_bytes());
    ok = in->read_image(0, 0, 0, in->spec().nchannels, in->spec().format, pixels.data());
  }
  const std::string message = in ? in->geterror() : OIIO::geterror();
  if (ok) return true;
  // The reader cannot know why bytes are missing; a full file system is the common cause.
  struct statvfs fs {};
  if (::statvfs(temp_.c_str(), &fs) == 0 && (fs.f_bfree == 0 || fs.f_bavail == 0))
    open_error_ = ENOSPC;
  else
    read_back_failure_ = "the written file does not read back (" +
                         (message.empty() ? std::string("no reason given") : message) + ")";
  return false;
}

std::string CheckedWrite::cause() {
  const std::string library = out_ ? out_->geterror() : std::string();
  const int err = open_error_ != 0 ? open_error_ : proxy_ ? proxy_->firstError() : 0;
  if (err != 0) return std::strerror(err);
  if (!read_back_failure_.empty()) return read_back_failure_;
  return library.empty() ? std::string("the image library gave no reason") : library;
}

}  // namespace artcam::io_checked
