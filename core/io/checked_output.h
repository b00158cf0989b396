// SPDX-License-Identifier: Apache-2.0
// Every OpenImageIO writer's bytes go through a file of ours, so no write error goes unseen
// (image module only, oiio_io.h).
//
// OpenImageIO 2.4's PNG writer does not check what fwrite returns (a full disk gave a PNG cut
// mid-IDAT and "wrote", exit 0); its JPEG writer leaves libjpeg's error_exit at the default,
// which calls exit() on a write error. So the formats that take an IOProxy and were seen to write
// through one the same bytes (takesCheckedOutput: PNG, JPEG, OpenEXR, HDR, BMP, Targa, PNM,
// WebP, GIF, DPX, JPEG 2000 in 2.4) are given CheckedOutput, a proxy over a descriptor that:
// - records the first failed write's errno and from then on writes nothing, yet reports every
//   write as done, so no codec reaches a fatal path of its own (the pixels are lost anyway);
// - is closed and checked after ImageOutput::close(): a recorded error or a failed close(2)
//   fails the save before atomic_file.h renames the temporary, naming errno's text.
// The others open the file themselves: TIFF (libtiff checks its own writes) is trusted to
// report them; the rest (SGI, ICO, FITS, RLA, HEIF) are read back whole once written
// (CheckedWrite::close), besides their own errors and the fsync before the rename.
#pragma once

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace artcam::io_checked {

class CheckedOutput final : public OIIO::Filesystem::IOProxy {
 public:
  // Creates (truncates) `path`; null with errno set when it cannot.
  static std::unique_ptr<CheckedOutput> create(const std::string& path);
  ~CheckedOutput() override;
  CheckedOutput(const CheckedOutput&) = delete;
  CheckedOutput& operator=(const CheckedOutput&) = delete;

  const char* proxytype() const override { return "artcam-checked"; }
  // The codec's close: nothing is buffered here, so the descriptor stays open for finish().
  void close() override {}
  bool seek(int64_t offset) override;
  size_t read(void* buf, size_t size) override;
  size_t write(const void* buf, size_t size) override;
  size_t pread(void* buf, size_t size, int64_t offset) override;
  size_t pwrite(const void* buf, size_t size, int64_t offset) override;
  size_t size() const override;
  void flush() const override {}

  // The errno of the first write that failed; 0 when none did.
  int firstError() const { return first_error_.load(); }
  // Closes the descriptor; false (firstError() then set) when a write or the close failed.
  bool finish();

 private:
  explicit CheckedOutput(int fd, const std::string& path);
  bool writeAt(const void* buf, size_t size, int64_t offset);
  int fd_ = -1;
  std::atomic<int> first_error_{0};
  std::atomic<int64_t> extent_{0};  // the file's length had every write succeeded
};

// One image write's open, close and cause: `out` opened on `temp` through a CheckedOutput when
// its format takes one. It owns `out`, and the destructor closes and destroys it, so no writer
// touches the file once the save is over (a writer may write at its destruction: HEIF does).
class CheckedWrite {
 public:
  explicit CheckedWrite(std::unique_ptr<OIIO::ImageOutput> out) : out_(std::move(out)) {}
  ~CheckedWrite();
  CheckedWrite(const CheckedWrite&) = delete;
  CheckedWrite& operator=(const CheckedWrite&) = delete;

  OIIO::ImageOutput& output() { return *out_; }
  // false: the file could not be made or the writer refused the spec; see cause().
  bool open(const std::string& temp, const OIIO::ImageSpec& spec);
  // The same for a file of several parts (subimages), `specs` in order: the first is written
  // after this open, each next one after out.open(temp, spec, AppendSubimage).
  bool open(const std::string& temp, const std::vector<OIIO::ImageSpec>& specs);
  // out.close(), then the proxy's finish() (or, without a proxy, the read-back); false when
  // either failed; see cause().
  bool close();
  // What a failure reports: the failed write's (or open's) errno text when there was one, else
  // the library's message (out.geterror(), read here, so its queue is emptied either way).
  std::string cause();

 private:
  bool readsBack();
  std::unique_ptr<OIIO::ImageOutput> out_;
  std::string temp_;
  std::unique_ptr<CheckedOutput> proxy_;
  int open_error_ = 0;  // open's errno, or what a failed read-back was traced to
  std::string read_back_failure_;
  bool closed_ = false;
};

}  // namespace artcam::io_checked
