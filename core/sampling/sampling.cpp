// SPDX-License-Identifier: Apache-2.0
#include "core/sampling/sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {

void cubicWeights(double t, double w[4]) {
  // Keys' kernel with a = −0.5 evaluated at distances 1 + t, t, 1 − t, 2 − t.
  const double t2 = t * t, t3 = t2 * t;
  w[0] = -0.5 * t3 + t2 - 0.5 * t;
  w[1] = 1.5 * t3 - 2.5 * t2 + 1.0;
  w[2] = -1.5 * t3 + 2.0 * t2 + 0.5 * t;
  w[3] = 0.5 * t3 - 0.5 * t2;
}

Sampler::Sampler(const ImageF& source, Filter filter, EdgeMode edge)
    : source_(source),
      filter_(filter),
      extend_(edge == EdgeMode::Extend),
      channels_(source.channels),
      out_channels_(source.alpha_channel >= 0 ? source.channels : source.channels + 1),
      out_alpha_(source.alpha_channel >= 0 ? source.alpha_channel : source.channels),
      append_alpha_(source.alpha_channel < 0) {
  checkSourceImage(source);
}

void checkSourceImage(const ImageF& source) {
  if (source.empty() || source.channels > 4 ||
      source.data.size() != static_cast<size_t>(source.width) * static_cast<size_t>(source.height) *
                                 static_cast<size_t>(source.channels))
    throw std::invalid_argument("the source image is empty, has more than 4 channels, or its "
                                "data does not match its size");
  if (source.alpha_channel >= source.channels)
    throw std::invalid_argument("the source image's alpha channel index is out of range");
}

void Sampler::clear(float* out) const { std::fill(out, out + out_channels_, 0.0f); }

void Sampler::sample(double sx, double sy, float* out) const {
  const double fx = sx - 0.5, fy = sy - 0.5;
  switch (filter_) {
    case Filter::Nearest: nearest(fx, fy, out); return;
    case Filter::Bilinear: bilinear(fx, fy, out); return;
    case Filter::Bicubic: bicubic(fx, fy, out); return;
  }
  clear(out);
}

void Sampler::finish(const float* sum, double coverage, float* out) const {
  for (int c = 0; c < channels_; ++c) out[c] = sum[c];
  if (append_alpha_) out[out_alpha_] = static_cast<float>(std::clamp(coverage, 0.0, 1.0));
  else out[out_alpha_] = std::clamp(out[out_alpha_], 0.0f, 1.0f);
}

void Sampler::nearest(double fx, double fy, float* out) const {
  // The pixel whose square contains the point; the negated test also rejects NaN.
  const double w = source_.width, h = source_.height;
  if (!(fx >= -0.5 && fx < w - 0.5 && fy >= -0.5 && fy < h - 0.5) &&
      !(extend_ && fx > -1.0 && fx < w && fy > -1.0 && fy < h))
    return clear(out);
  const int x = std::min(static_cast<int>(fx + 0.5), source_.width - 1);
  const int y = std::min(static_cast<int>(fy + 0.5), source_.height - 1);
  const float* p = source_.pixel(x, y);
  for (int c = 0; c < channels_; ++c) out[c] = p[c];
  if (append_alpha_) out[out_alpha_] = 1.0f;
}

void Sampler::bilinear(double fx, double fy, float* out) const {
  const int w = source_.width, h = source_.height;
  if (!(fx > -1.0 && fx < w && fy > -1.0 && fy < h)) return clear(out);
  const double flx = std::floor(fx), fly = std::floor(fy);
  const int x0 = static_cast<int>(flx), y0 = static_cast<int>(fly);
  const float ax = static_cast<float>(fx - flx), ay = static_cast<float>(fy - fly);
  const float wx[2] = {1.0f - ax, ax}, wy[2] = {1.0f - ay, ay};
  float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < w && y0 + 1 < h) {
    // Interior: all four taps exist, coverage is exactly 1.
    for (int j = 0; j < 2; ++j) {
      const float* row = source_.pixel(x0, y0 + j);
      for (int c = 0; c < channels_; ++c)
        sum[c] += wy[j] * (wx[0] * row[c] + wx[1] * row[c + channels_]);
    }
    return finish(sum, 1.0, out);
  }
  double coverage = 0.0;
  for (int j = 0; j < 2; ++j) {
    int y = y0 + j;
    if (y < 0 || y >= h) {
      if (!extend_) continue;
      y = std::clamp(y, 0, h - 1);
    }
    for (int i = 0; i < 2; ++i) {
      int x = x0 + i;
      if (x < 0 || x >= w) {
        if (!extend_) continue;
        x = std::clamp(x, 0, w - 1);
      }
      const float wt = wx[i] * wy[j];
      const float* p = source_.pixel(x, y);
      for (int c = 0; c < channels_; ++c) sum[c] += wt * p[c];
      coverage += wt;
    }
  }
  finish(sum, coverage, out);
}

void Sampler::bicubic(double fx, double fy, float* out) const {
  const int w = source_.width, h = source_.height;
  if (!(fx > -2.0 && fx < w + 1.0 && fy > -2.0 && fy < h + 1.0)) return clear(out);
  const double flx = std::floor(fx), fly = std::floor(fy);
  const int x0 = static_cast<int>(flx) - 1, y0 = static_cast<int>(fly) - 1;
  double wxd[4], wyd[4];
  cubicWeights(fx - flx, wxd);
  cubicWeights(fy - fly, wyd);
  float wx[4], wy[4];
  for (int i = 0; i < 4; ++i) {
    wx[i] = static_cast<float>(wxd[i]);
    wy[i] = static_cast<float>(wyd[i]);
  }
  float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const bool interior = x0 >= 0 && y0 >= 0 && x0 + 3 < w && y0 + 3 < h;
  double coverage = 0.0;
  for (int j = 0; j < 4; ++j) {
    int y = y0 + j;
    if (y < 0 || y >= h) {
      if (!extend_) continue;
      y = std::clamp(y, 0, h - 1);
    }
    float row_sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    double row_cover = 0.0;
    for (int i = 0; i < 4; ++i) {
      int x = x0 + i;
      if (x < 0 || x >= w) {
        if (!extend_) continue;
        x = std::clamp(x, 0, w - 1);
      }
      const float* p = source_.pixel(x, y);
      for (int c = 0; c < channels_; ++c) row_sum[c] += wx[i] * p[c];
      row_cover += wxd[i];
    }
    for (int c = 0; c < channels_; ++c) sum[c] += wy[j] * row_sum[c];
    coverage += wyd[j] * row_cover;
  }
  // The weights sum to 1 in the interior; say so exactly rather than 1 ± rounding.
  finish(sum, interior ? 1.0 : coverage, out);
}

}  // namespace artcam
