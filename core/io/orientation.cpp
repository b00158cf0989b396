// SPDX-License-Identifier: Apache-2.0
#include "core/io/orientation.h"

#include <cstdint>
#include <cstring>

namespace artcam {

int validOrientation(int value) { return value >= 1 && value <= 8 ? value : 1; }

bool orientationSwapsAxes(int orientation) { return orientation >= 5 && orientation <= 8; }

int inverseOrientation(int orientation) {
  const int o = validOrientation(orientation);
  return o == 6 ? 8 : o == 8 ? 6 : o;
}

void reorientPixels(const void* stored, int width, int height, size_t pixel_bytes, int orientation,
                    void* upright) {
  const auto* in = static_cast<const std::uint8_t*>(stored);
  auto* out = static_cast<std::uint8_t*>(upright);
  const int o = validOrientation(orientation);
  const bool swap = orientationSwapsAxes(o);
  const int out_w = swap ? height : width, out_h = swap ? width : height;
  // For each upright pixel (x, y), the stored pixel (sx, sy) it shows (the table in the header).
  for (int y = 0; y < out_h; ++y) {
    for (int x = 0; x < out_w; ++x) {
      int sx = x, sy = y;
      switch (o) {
        case 2:
          sx = width - 1 - x;
          break;
        case 3:
          sx = width - 1 - x, sy = height - 1 - y;
          break;
        case 4:
          sy = height - 1 - y;
          break;
        case 5:
          sx = y, sy = x;
          break;
        case 6:
          sx = y, sy = height - 1 - x;
          break;
        case 7:
          sx = width - 1 - y, sy = height - 1 - x;
          break;
        case 8:
          sx = width - 1 - y, sy = x;
          break;
        default:
          break;
      }
      std::memcpy(
          out + (static_cast<size_t>(y) * static_cast<size_t>(out_w) + static_cast<size_t>(x)) *
                    pixel_bytes,
          in + (static_cast<size_t>(sy) * static_cast<size_t>(width) + static_cast<size_t>(sx)) *
                   pixel_bytes,
          pixel_bytes);
    }
  }
}

}  // namespace artcam
