// SPDX-License-Identifier: Apache-2.0
// 8/16-bit stored samples to linear float through a table of the exact transfer function (one
// entry per code value), the readers' integer path: image_io.cpp (the module's) and
// jpeg_file.cpp (JPEG without it) decode with this one table, so they give the same floats.
#pragma once

#include "core/colour/transfer.h"
#include "core/model/image.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace artcam::integer_decode {

template <class T>
std::vector<float> table(const Transfer& transfer) {
  constexpr int kMax = std::numeric_limits<T>::max();
  std::vector<float> values(kMax + 1);
  for (int v = 0; v <= kMax; ++v)
    values[static_cast<size_t>(v)] = static_cast<float>(transfer.decode(static_cast<double>(v) / kMax));
  return values;
}

// Colour through the table, alpha (never encoded) scaled to [0, 1].
template <class T>
void decode(const T* stored, size_t count, const Transfer& transfer, ImageF& image) {
  constexpr float kMax = static_cast<float>(std::numeric_limits<T>::max());
  const std::vector<float> values = table<T>(transfer);
  const size_t channels = static_cast<size_t>(image.channels);
  for (size_t k = 0; k < count; ++k) {
    const bool alpha = static_cast<int>(k % channels) == image.alpha_channel;
    image.data[k] = alpha ? static_cast<float>(stored[k]) / kMax : values[stored[k]];
  }
}

}  // namespace artcam::integer_decode
