// SPDX-License-Identifier: Apache-2.0
// Memory for whole images: zero-filled bytes, aligned to 2 MiB and, on Linux, advised
// to live on transparent huge pages before the first touch.
//
// Why: a warp reads its source along tilted, curved rows, so every output row touches a new
// 4 KiB page of the source every few dozen pixels; with 4 KiB pages a 24 Mpix photo spans
// 17 000 pages, far more than the TLB holds, and the sampler waits on page walks (measured:
// most of its time on the source load). 2 MiB pages cut that to ~35. Where the kernel refuses
// (THP "never"), this is plain aligned memory.
//
// Zeroed by default. A buffer its producer overwrites whole (a decoder's raster, a render's
// output) asks for Uninitialised: zeroing 72 MB first costs a pass and, worse, takes every page
// fault on the allocating thread; left untouched, the pages are faulted in by whichever threads
// write them, in parallel and while the data is hot.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace artcam {

class PixelBuffer {
 public:
  enum class Init { Zeroed, Uninitialised };
  PixelBuffer() = default;
  explicit PixelBuffer(std::size_t bytes, Init init = Init::Zeroed) : size_(bytes) {
    if (bytes == 0) return;
    constexpr std::size_t kHuge = std::size_t{2} << 20;
    const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
    void* p = std::aligned_alloc(kHuge, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure leaves ordinary pages
#endif
    if (init == Init::Zeroed) std::memset(p, 0, bytes);
    data_.reset(static_cast<std::uint8_t*>(p));
  }

  std::uint8_t* data() { return data_.get(); }
  const std::uint8_t* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint8_t& operator[](std::size_t i) { return data_.get()[i]; }
  const std::uint8_t& operator[](std::size_t i) const { return data_.get()[i]; }
  std::uint8_t* begin() { return data(); }
  std::uint8_t* end() { return data() + size_; }
  const std::uint8_t* begin() const { return data(); }
  const std::uint8_t* end() const { return data() + size_; }

 private:
  struct Free {
    void operator()(std::uint8_t* p) const { std::free(p); }
  };
  std::unique_ptr<std::uint8_t, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace artcam
