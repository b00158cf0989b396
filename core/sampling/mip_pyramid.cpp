// SPDX-License-Identifier: Apache-2.0
#include "core/sampling/mip_pyramid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace artcam {
namespace {

ImageF halve(const ImageF& in) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2, c = in.channels;
  ImageF out(w, h, c, in.alpha_channel);
  for (int y = 0; y < h; ++y) {
    const int y0 = 2 * y, y1 = std::min(2 * y + 1, in.height - 1);
    for (int x = 0; x < w; ++x) {
      const int x0 = 2 * x, x1 = std::min(2 * x + 1, in.width - 1);
      const float* a = in.pixel(x0, y0);
      const float* b = in.pixel(x1, y0);
      const float* d = in.pixel(x0, y1);
      const float* e = in.pixel(x1, y1);
      float* o = out.pixel(x, y);
      for (int k = 0; k < c; ++k) o[k] = 0.25f * (a[k] + b[k] + d[k] + e[k]);
    }
  }
  return out;
}

// One row of a 2×2 box level; C > 0 fixes the channel count at compile time (the RGBA8
// previews), so the inner loop unrolls and vectorises. Columns with both sources inside go
// first, without a bounds test; an odd last column repeats.
template <int C>
void halveRow(const std::uint8_t* r0, const std::uint8_t* r1, std::uint8_t* o, int in_width,
              int w, int channels) {
  const int c = C > 0 ? C : channels;
  const int whole = in_width / 2;
  for (int x = 0; x < whole; ++x) {
    const std::uint8_t* a = r0 + 2 * x * c;
    const std::uint8_t* b = r1 + 2 * x * c;
    for (int k = 0; k < c; ++k)
      o[x * c + k] = static_cast<std::uint8_t>((a[k] + a[k + c] + b[k] + b[k + c] + 2) >> 2);
  }
  for (int x = whole; x < w; ++x) {
    const int x0 = 2 * x * c;
    for (int k = 0; k < c; ++k)
      o[x * c + k] = static_cast<std::uint8_t>((2 * r0[x0 + k] + 2 * r1[x0 + k] + 2) >> 2);
  }
}

// One 2×2 box level of 8-bit samples, rounded to nearest; the last row/column repeats.
ConstImageView halveBytes(const ConstImageView& in, PixelBuffer& storage) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2, c = in.channels;
  // Every byte is written below.
  storage = PixelBuffer(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(c),
                        PixelBuffer::Init::Uninitialised);
  const ConstImageView out = packedView<const void>(storage.data(), w, h, c, PixelType::UInt8, in.alpha_channel);
  for (int y = 0; y < h; ++y) {
    const auto* r0 = static_cast<const std::uint8_t*>(in.row(2 * y));
    const auto* r1 = static_cast<const std::uint8_t*>(in.row(std::min(2 * y + 1, in.height - 1)));
    std::uint8_t* o = storage.data() + static_cast<size_t>(y) * static_cast<size_t>(w) * static_cast<size_t>(c);
    if (c == 4)
      halveRow<4>(r0, r1, o, in.width, w, c);
    else
      halveRow<0>(r0, r1, o, in.width, w, c);
  }
  return out;
}

}  // namespace

StoredMipPyramid::StoredMipPyramid(const ConstImageView& base, int min_size) {
  if (base.empty() || base.type != PixelType::UInt8)
    throw std::invalid_argument("an 8-bit mip pyramid needs a non-empty 8-bit image");
  views_.push_back(base);
  owned_.reserve(32);
  while (std::max(views_.back().width, views_.back().height) / 2 >= std::max(1, min_size)) {
    owned_.emplace_back();
    views_.push_back(halveBytes(views_.back(), owned_.back()));
  }
}

int StoredMipPyramid::levelFor(double footprint) const {
  if (!(footprint > 1.0)) return 0;
  const int k = static_cast<int>(std::floor(std::log2(footprint) + 1e-9));
  return std::clamp(k, 0, levels() - 1);
}

MipPyramid::MipPyramid(ImageF base, int min_size) {
  if (base.empty()) throw std::invalid_argument("a mip pyramid needs a non-empty image");
  levels_.push_back(std::move(base));
  while (std::max(levels_.back().width, levels_.back().height) / 2 >= std::max(1, min_size))
    levels_.push_back(halve(levels_.back()));
}

int MipPyramid::levelFor(double footprint) const {
  if (!(footprint > 1.0)) return 0;
  const int k = static_cast<int>(std::floor(std::log2(footprint) + 1e-9));
  return std::clamp(k, 0, levels() - 1);
}

}  // namespace artcam
