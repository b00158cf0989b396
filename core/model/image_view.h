// SPDX-License-Identifier: Apache-2.0
// Typed, strided views of interleaved images, so the warp reads 8-bit, 16-bit and float pixels
// where they lie instead of converting a whole photo to float first (288 MB for 24 Mpix).
//
// Conventions (image.h): pixel (x, y) covers [x, x+1)×[y, y+1), its centre is (x + 0.5, y + 0.5);
// 1 to 4 interleaved channels; colour PREMULTIPLIED by alpha when there is an alpha channel.
// Integer samples are numbers on the scale 0..255 (uint8) or 0..65535 (uint16) in whatever
// transfer the caller keeps them (the warp interpolates the stored numbers, as OpenCV's remap
// does; ImageF holds linear light). An alpha channel's full scale is the type's maximum.
#pragma once

#include "core/model/image.h"

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace artcam {

enum class PixelType { UInt8, UInt16, Float };

// Bytes per sample and the value that means "alpha 1" for each type.
constexpr int pixelTypeSize(PixelType t) {
  return t == PixelType::UInt8 ? 1 : t == PixelType::UInt16 ? 2 : 4;
}
constexpr float pixelTypeFullScale(PixelType t) {
  return t == PixelType::UInt8 ? 255.0f : t == PixelType::UInt16 ? 65535.0f : 1.0f;
}

template <class T>
struct ImageViewBase {
  T* data = nullptr;           // first sample of pixel (0, 0)
  int width = 0;
  int height = 0;
  int channels = 0;            // 1..4
  int alpha_channel = -1;      // index of alpha, or -1
  PixelType type = PixelType::Float;
  std::ptrdiff_t row_bytes = 0;  // stride between rows (may exceed width · channels · size)

  bool empty() const { return data == nullptr || width <= 0 || height <= 0 || channels <= 0; }
  int pixelBytes() const { return channels * pixelTypeSize(type); }
  T* row(int y) const {
    // The byte arithmetic goes through unsigned char so const-ness follows T.
    using Byte = std::conditional_t<std::is_const_v<T>, const unsigned char, unsigned char>;
    return static_cast<T*>(static_cast<Byte*>(data) + static_cast<std::ptrdiff_t>(y) * row_bytes);
  }
};

using ImageView = ImageViewBase<void>;
using ConstImageView = ImageViewBase<const void>;

// A packed view of caller-owned memory (row_bytes = width · channels · size).
template <class T>
ImageViewBase<T> packedView(T* data, int width, int height, int channels, PixelType type,
                            int alpha_channel = -1) {
  ImageViewBase<T> v;
  v.data = data;
  v.width = width;
  v.height = height;
  v.channels = channels;
  v.alpha_channel = alpha_channel;
  v.type = type;
  v.row_bytes = static_cast<std::ptrdiff_t>(width) * channels * pixelTypeSize(type);
  return v;
}

inline ConstImageView viewOf(const ImageF& image) {
  return packedView<const void>(image.data.data(), image.width, image.height, image.channels,
                                PixelType::Float, image.alpha_channel);
}
inline ImageView viewOf(ImageF& image) {
  return packedView<void>(image.data.data(), image.width, image.height, image.channels,
                          PixelType::Float, image.alpha_channel);
}

}  // namespace artcam
