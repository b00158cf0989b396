// SPDX-License-Identifier: Apache-2.0
#include "ui/image_convert.h"

#include <QRgb>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace artcam::ui {
namespace {

constexpr int kLutSize = 4096;

// Linear [0, 1] sampled at kLutSize points → sRGB byte. Built once, thread-safe (static init).
const std::array<std::uint8_t, kLutSize>& srgbLut() {
  static const std::array<std::uint8_t, kLutSize> lut = [] {
    std::array<std::uint8_t, kLutSize> t{};
    for (int i = 0; i < kLutSize; ++i) {
      const double v = static_cast<double>(i) / (kLutSize - 1);
      const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      t[static_cast<size_t>(i)] =
          static_cast<std::uint8_t>(std::lround(std::clamp(e, 0.0, 1.0) * 255.0));
    }
    return t;
  }();
  return lut;
}

inline int encode(float linear, const std::array<std::uint8_t, kLutSize>& lut) {
  // NaN fails both comparisons and lands on 0: a broken pixel shows black, never garbage.
  const float c = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
  return lut[static_cast<size_t>(c * (kLutSize - 1) + 0.5f)];
}

}  // namespace

QImage qimageFromLinear(const ImageF& image) {
  if (image.empty()) return {};
  QImage out(image.width, image.height, QImage::Format_ARGB32_Premultiplied);
  if (out.isNull()) return {};  // allocation failed: the caller shows nothing
  const auto& lut = srgbLut();
  const int ch = image.channels;
  const int a_index = image.alpha_channel;
  for (int y = 0; y < image.height; ++y) {
    auto* row = reinterpret_cast<QRgb*>(out.scanLine(y));
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      float alpha = a_index >= 0 ? p[a_index] : 1.0f;
      alpha = alpha > 0.0f ? (alpha < 1.0f ? alpha : 1.0f) : 0.0f;
      if (alpha <= 0.0f) {
        row[x] = 0;
        continue;
      }
      const float inv = 1.0f / alpha;
      int r = 0, g = 0, b = 0;
      if (ch >= 3) {
        r = encode(p[0] * inv, lut);
        g = encode(p[1] * inv, lut);
        b = encode(p[2] * inv, lut);
      } else {
        r = g = b = encode(p[0] * inv, lut);
      }
      const int a8 = static_cast<int>(alpha * 255.0f + 0.5f);
      // Re-premultiply in 8 bits, as ARGB32_Premultiplied requires.
      row[x] = qRgba((r * a8 + 127) / 255, (g * a8 + 127) / 255, (b * a8 + 127) / 255, a8);
    }
  }
  return out;
}

ImageF boxDownscale(const ImageF& image, int max_side) {
  const int longest = std::max(image.width, image.height);
  if (image.empty() || max_side <= 0 || longest <= max_side) return image;
  const int f = (longest + max_side - 1) / max_side;
  const int w = (image.width + f - 1) / f;
  const int h = (image.height + f - 1) / f;
  ImageF out(w, h, image.channels, image.alpha_channel);
  const int ch = image.channels;
  std::vector<double> sum(static_cast<size_t>(ch));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::fill(sum.begin(), sum.end(), 0.0);
      const int y1 = std::min(image.height, (y + 1) * f);
      const int x1 = std::min(image.width, (x + 1) * f);
      int n = 0;
      for (int sy = y * f; sy < y1; ++sy)
        for (int sx = x * f; sx < x1; ++sx, ++n) {
          const float* p = image.pixel(sx, sy);
          for (int c = 0; c < ch; ++c) sum[static_cast<size_t>(c)] += p[c];
        }
      float* q = out.pixel(x, y);
      for (int c = 0; c < ch; ++c) q[c] = static_cast<float>(sum[static_cast<size_t>(c)] / n);
    }
  }
  return out;
}

}  // namespace artcam::ui
