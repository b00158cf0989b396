// SPDX-License-Identifier: Apache-2.0
// The engine's image: interleaved float, LINEAR light, PREMULTIPLIED alpha when there is an
// alpha channel (colour is linear inside the engine; alpha is the homogeneous
// weight). Pixel (x, y) covers [x, x+1)×[y, y+1); its centre is (x + 0.5, y + 0.5).
#pragma once

#include <cstddef>
#include <vector>

namespace artcam {

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 0;        // 1..4
  int alpha_channel = -1;  // index of alpha, or -1
  std::vector<float> data; // width * height * channels

  ImageF() = default;
  ImageF(int w, int h, int c, int alpha = -1)
      : width(w), height(h), channels(c), alpha_channel(alpha),
        data(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(c), 0.0f) {}

  bool empty() const { return width <= 0 || height <= 0 || channels <= 0; }
  float* pixel(int x, int y) {
    return data.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * static_cast<size_t>(channels);
  }
  const float* pixel(int x, int y) const {
    return data.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * static_cast<size_t>(channels);
  }
};

}  // namespace artcam
