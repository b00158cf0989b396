// SPDX-License-Identifier: Apache-2.0
// Large scratch blocks a render allocates afresh every time, recycled between renders.
//
// Why: freed, a block of megabytes goes back to the system (glibc unmaps large blocks and trims
// the heap's top), so the next render touches every page of its new block for the first time
// and the kernel faults and zeroes each one (the rational kernel's refined cells of a strong
// twist: about 1,500 pages a render). Kept here instead, a released block goes to the next
// request it fits, whose pages are already mapped. At most kKeepBlocks blocks and kKeepBytes
// in all are kept (8: a piecewise render holds a probe mesh, its mesh and a band block per
// thread at once, and the rational kernel up to four); a block is handed out only for a
// request of at least half its size, so a small request never holds a large block.
// Thread-safe; a block is uninitialised memory, aligned to 64 bytes.
#pragma once

#include <cstddef>
#include <utility>

namespace artcam {

class ScratchBlock {
 public:
  ScratchBlock() = default;
  ScratchBlock(ScratchBlock&& other) noexcept { swap(other); }
  ScratchBlock& operator=(ScratchBlock&& other) noexcept {
    ScratchBlock(std::move(other)).swap(*this);
    return *this;
  }
  ScratchBlock(const ScratchBlock&) = delete;
  ScratchBlock& operator=(const ScratchBlock&) = delete;
  ~ScratchBlock();  // back to the pool

  void* data() const { return data_; }
  std::size_t bytes() const { return bytes_; }  // the block's size (at least the request)

 private:
  friend ScratchBlock takeScratch(std::size_t bytes);
  void swap(ScratchBlock& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(bytes_, other.bytes_);
  }
  void* data_ = nullptr;
  std::size_t bytes_ = 0;
};

// A block of at least `bytes` (none for 0); throws std::bad_alloc as operator new does.
ScratchBlock takeScratch(std::size_t bytes);

// What the pool keeps (tests).
constexpr int kScratchKeepBlocks = 8;
constexpr std::size_t kScratchKeepBytes = std::size_t{64} << 20;
std::size_t scratchKeptBytes();

}  // namespace artcam
