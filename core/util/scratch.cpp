// SPDX-License-Identifier: Apache-2.0
#include "core/util/scratch.h"

#include <algorithm>
#include <mutex>
#include <new>
#include <vector>

namespace artcam {
namespace {

constexpr std::align_val_t kAlign{64};

struct Pool {
  std::mutex mutex;
  std::vector<std::pair<void*, std::size_t>> kept;  // oldest first
  std::size_t kept_bytes = 0;
};

Pool& pool() {
  // Never destroyed: blocks released during static destruction still find it (and are freed by
  // the process's end).
  static Pool* p = new Pool;
  return *p;
}

}  // namespace

ScratchBlock takeScratch(std::size_t bytes) {
  ScratchBlock block;
  if (bytes == 0) return block;
  {
    Pool& p = pool();
    const std::lock_guard<std::mutex> lock(p.mutex);
    // The smallest kept block that fits and is not more than twice the request.
    auto best = p.kept.end();
    for (auto it = p.kept.begin(); it != p.kept.end(); ++it)
      if (it->second >= bytes && it->second / 2 <= bytes && (best == p.kept.end() || it->second < best->second))
        best = it;
    if (best != p.kept.end()) {
      block.data_ = best->first;
      block.bytes_ = best->second;
      p.kept_bytes -= best->second;
      p.kept.erase(best);
      return block;
    }
  }
  block.data_ = ::operator new(bytes, kAlign);
  block.bytes_ = bytes;
  return block;
}

ScratchBlock::~ScratchBlock() {
  if (!data_) return;
  Pool& p = pool();
  std::vector<std::pair<void*, std::size_t>> drop;
  {
    const std::lock_guard<std::mutex> lock(p.mutex);
    if (bytes_ <= kScratchKeepBytes) {
      p.kept.emplace_back(data_, bytes_);
      p.kept_bytes += bytes_;
      data_ = nullptr;
      // Over the limits: the oldest blocks go.
      while (p.kept.size() > static_cast<std::size_t>(kScratchKeepBlocks) || p.kept_bytes > kScratchKeepBytes) {
        drop.push_back(p.kept.front());
        p.kept_bytes -= p.kept.front().second;
        p.kept.erase(p.kept.begin());
      }
    }
  }
  if (data_) ::operator delete(data_, kAlign);
  for (const auto& [block, size] : drop) ::operator delete(block, kAlign);
}

std::size_t scratchKeptBytes() {
  Pool& p = pool();
  const std::lock_guard<std::mutex> lock(p.mutex);
  return p.kept_bytes;
}

}  // namespace artcam
