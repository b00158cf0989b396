// SPDX-License-Identifier: Apache-2.0
// The fast depth-of-field blur (depth_of_field.h, stackBlur): a stack of halo-masked Gaussian
// levels σ_1 < σ_2 < … (ratio `level_ratio`), each pixel blending its two bracketing levels.
//
// What makes it fast on 24 Mpix (a σ = 16 blur does not need full resolution):
// - Coarse levels (σ ≥ shrink_from_sigma) blur a 2×, 4×, … box-shrunk copy of the masked image
//   with a small separable kernel; they are at most a quarter of the image and kept whole. All
//   their masked shrinks come from one read of the full-resolution image.
// - Fine levels (σ below that) are blurred at full resolution, but only band by band and only
//   over the columns whose pixels need them (plus the kernel radius), so no full-resolution
//   level image is ever written and a level that no pixel of a band uses costs nothing there.
// - One pass over the output then blends each pixel from its two levels: the full-resolution
//   work is a couple of passes, not two per level.
// - The separable passes are flat row sums over zero-padded rows (addScaled), which the
//   compiler vectorises.
// Every level is the same as in a level-by-level stack (same mask, kernels, shrink, tent
// read-back), so the error against exactBlur is that of the stack itself.
#include "core/effects/depth_of_field.h"

#include "core/effects/blur_inputs.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace artcam {

namespace {

constexpr int kC = 5;  // premultiplied r, g, b, a times the halo mask, and the mask itself
constexpr uint16_t kSharp = 0xffff;  // "no level": the pixel stays sharp

// A 5-channel image without zero-filling it first.
struct Buffer5 {
  std::unique_ptr<float[]> data;
  int w = 0, h = 0;
  Buffer5() = default;
  Buffer5(int width, int height)
      : data(new float[static_cast<size_t>(width) * static_cast<size_t>(height) * kC]),
        w(width),
        h(height) {}
  float* row(int y) const {
    return data.get() + static_cast<size_t>(y) * static_cast<size_t>(w) * kC;
  }
};

std::vector<float> gaussianKernel(double sigma, int& radius) {
  radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<float> g(static_cast<size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    const double v = std::exp(-0.5 * k * k / (sigma * sigma));
    g[static_cast<size_t>(k + radius)] = static_cast<float>(v);
    sum += v;
  }
  for (float& v : g) v = static_cast<float>(v / sum);
  return g;
}

// dst[i] += g·src[i], i < n: in blocks of 8 that the compiler turns into vector adds at -O2
// (the blur is a sum of such rows: flat, with no per-pixel bounds or channel loops).
void addScaled(float* __restrict dst, const float* __restrict src, float g, size_t n) {
  size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (size_t j = 0; j < 8; ++j) dst[i + j] += g * src[i + j];
  for (; i < n; ++i) dst[i] += g * src[i];
}

// out[x] = Σ_k g[k]·in[x + k], x < count, over 5-channel pixels: `padded` holds the count + 2r
// input pixels from x − r on (zeros outside the image), so every k is one flat addScaled.
void horizontalPass(const float* padded, const std::vector<float>& g, int r, int count,
                    float* out) {
  const size_t n = static_cast<size_t>(count) * kC;
  std::fill(out, out + n, 0.0f);
  for (int k = 0; k <= 2 * r; ++k)
    addScaled(out, padded + static_cast<size_t>(k) * kC, g[static_cast<size_t>(k)], n);
}

// Separable Gaussian of a (small, shrunk) 5-channel image, zero outside. The result is written
// over the input's storage: one fresh buffer per level instead of two (fresh pages cost).
Buffer5 blur5(Buffer5 in, double sigma, int threads) {
  const int w = in.w, h = in.h;
  int r = 0;
  const std::vector<float> g = gaussianKernel(sigma, r);
  Buffer5 tmp(w, h);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 32;
  parallelForRows(h, po, [&](int y0, int y1) {
    std::vector<float> padded(static_cast<size_t>(w + 2 * r) * kC, 0.0f);
    for (int y = y0; y < y1; ++y) {
      std::copy(in.row(y), in.row(y) + static_cast<size_t>(w) * kC, padded.begin() + r * kC);
      horizontalPass(padded.data(), g, r, w, tmp.row(y));
    }
  });
  const size_t row = static_cast<size_t>(w) * kC;
  parallelForRows(h, po, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* dst = in.row(y);  // the horizontal pass no longer needs it
      std::fill(dst, dst + row, 0.0f);
      const int k0 = std::max(-r, -y), k1 = std::min(r, h - 1 - y);
      for (int k = k0; k <= k1; ++k) {
        const float gk = g[static_cast<size_t>(k + r)];
        const float* src = tmp.row(y + k);
        addScaled(dst, src, gk, row);
      }
    }
  });
  return in;
}

struct Level {
  double sigma = 0.0;
  float threshold = 0.0f;  // the halo rule at this level: halo_ratio·σ
  int shrink = 1;
  Buffer5 blurred;            // shrink > 1: the whole blurred shrunk image
  std::vector<float> kernel;  // shrink == 1: the full-resolution kernel
  int radius = 0;
};

// The halo-masked inputs of the coarse levels (`coarse`, σ rising), each f×f box-averaged into
// its `blurred` buffer (a partial last block averaged over what it holds), in ONE pass over the
// full-resolution image: a pixel counts in a level when its σ ≥ the level's threshold, and the
// thresholds rise with the levels, so each pixel adds to a prefix of them. Bands of rows are
// aligned to the largest f, so every band owns whole shrunk rows of every level.
void maskedShrinkAll(const ImageF& rgba, const ImageF& sigma, const std::vector<Level*>& coarse,
                     int threads) {
  const int w = rgba.width, h = rgba.height;
  int largest = 1;
  std::vector<int> shift;
  for (Level* l : coarse) {
    l->blurred = Buffer5((w + l->shrink - 1) / l->shrink, (h + l->shrink - 1) / l->shrink);
    largest = std::max(largest, l->shrink);
    int k = 0;
    while ((1 << k) < l->shrink) ++k;
    shift.push_back(k);
  }
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = largest * std::max(1, 32 / largest);
  parallelForRows(h, po, [&](int y0, int y1) {
    for (const Level* l : coarse) {
      const int f = l->shrink;
      for (int sy = y0 / f; sy < (y1 + f - 1) / f; ++sy)
        std::fill(l->blurred.row(sy), l->blurred.row(sy) + static_cast<size_t>(l->blurred.w) * kC,
                  0.0f);
    }
    for (int y = y0; y < y1; ++y) {
      const float* s = sigma.pixel(0, y);
      const float* p = rgba.pixel(0, y);
      for (int x = 0; x < w; ++x) {
        const float* q = p + static_cast<size_t>(x) * 4;
        for (size_t i = 0; i < coarse.size() && s[x] >= coarse[i]->threshold; ++i) {
          float* o =
              coarse[i]->blurred.row(y >> shift[i]) + static_cast<size_t>(x >> shift[i]) * kC;
          o[0] += q[0], o[1] += q[1], o[2] += q[2], o[3] += q[3], o[4] += 1.0f;
        }
      }
    }
    for (const Level* l : coarse) {
      const int f = l->shrink;
      for (int sy = y0 / f; sy < (y1 + f - 1) / f; ++sy) {
        float* dst = l->blurred.row(sy);
        const int rows = std::min(h, sy * f + f) - sy * f;
        for (int sx = 0; sx < l->blurred.w; ++sx) {
          const float count = static_cast<float>(rows * (std::min(w, sx * f + f) - sx * f));
          for (int c = 0; c < kC; ++c)
            dst[static_cast<size_t>(sx) * kC + static_cast<size_t>(c)] /= count;
        }
      }
    }
  });
}

// Rows [y0, y1) × columns [x0, x1) of a full-resolution level, normalised by the blurred mask
// (a pixel the mask leaves empty falls back to its own colour), 4 channels, into `out`.
void fineLevelBand(const ImageF& rgba, const ImageF& sigma, const Level& level, int y0, int y1,
                   int x0, int x1, std::vector<float>& scratch, std::vector<float>& out) {
  const int w = rgba.width, h = rgba.height, r = level.radius;
  // The masked input row covers x0 − r … x1 + r, zero outside the image (horizontalPass).
  const int xa = std::max(0, x0 - r), xb = std::min(w, x1 + r);
  const int ya = std::max(0, y0 - r), yb = std::min(h, y1 + r);
  const size_t in_row = static_cast<size_t>(x1 - x0 + 2 * r) * kC;
  const size_t out_cols = static_cast<size_t>(x1 - x0);
  scratch.assign(in_row, 0.0f);
  scratch.resize(in_row + static_cast<size_t>(yb - ya) * out_cols * kC);
  float* masked = scratch.data();
  float* horizontal = scratch.data() + in_row;
  for (int y = ya; y < yb; ++y) {
    const float* s = sigma.pixel(0, y);
    const float* p = rgba.pixel(0, y);
    for (int x = xa; x < xb; ++x) {
      float* m = masked + static_cast<size_t>(x - (x0 - r)) * kC;
      const float keep = s[x] >= level.threshold ? 1.0f : 0.0f;
      for (int c = 0; c < 4; ++c)
        m[c] = keep * p[static_cast<size_t>(x) * 4 + static_cast<size_t>(c)];
      m[4] = keep;
    }
    horizontalPass(masked, level.kernel, r, x1 - x0,
                   horizontal + static_cast<size_t>(y - ya) * out_cols * kC);
  }
  out.resize(static_cast<size_t>(y1 - y0) * out_cols * 4);
  std::vector<float> acc(out_cols * kC);
  for (int y = y0; y < y1; ++y) {
    std::fill(acc.begin(), acc.end(), 0.0f);
    const int k0 = std::max(-r, -y), k1 = std::min(r, h - 1 - y);
    for (int k = k0; k <= k1; ++k) {
      const float gk = level.kernel[static_cast<size_t>(k + r)];
      const float* src = horizontal + static_cast<size_t>(y + k - ya) * out_cols * kC;
      addScaled(acc.data(), src, gk, acc.size());
    }
    float* o = out.data() + static_cast<size_t>(y - y0) * out_cols * 4;
    for (size_t x = 0; x < out_cols; ++x) {
      const float* v = acc.data() + x * kC;
      const float* fallback = rgba.pixel(x0 + static_cast<int>(x), y);
      for (int c = 0; c < 4; ++c)
        o[x * 4 + static_cast<size_t>(c)] = v[4] > 1e-6f ? v[c] / v[4] : fallback[c];
    }
  }
}

// A coarse level at full-resolution pixel (x, y): the tent (bilinear) read of the shrunk blur,
// then normalised as fineLevelBand does.
void coarseLevelAt(const ImageF& rgba, const Level& level, int x, int y, float* out) {
  const Buffer5& b = level.blurred;
  const float inv = 1.0f / static_cast<float>(level.shrink);
  const float fx =
      std::clamp((static_cast<float>(x) + 0.5f) * inv - 0.5f, 0.0f, static_cast<float>(b.w - 1));
  const float fy =
      std::clamp((static_cast<float>(y) + 0.5f) * inv - 0.5f, 0.0f, static_cast<float>(b.h - 1));
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, b.w - 1), y1 = std::min(y0 + 1, b.h - 1);
  const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
  const float* a = b.row(y0) + static_cast<size_t>(x0) * kC;
  const float* bb = b.row(y0) + static_cast<size_t>(x1) * kC;
  const float* c = b.row(y1) + static_cast<size_t>(x0) * kC;
  const float* d = b.row(y1) + static_cast<size_t>(x1) * kC;
  float v[kC];
  for (int k = 0; k < kC; ++k)
    v[k] = (1 - ty) * ((1 - tx) * a[k] + tx * bb[k]) + ty * ((1 - tx) * c[k] + tx * d[k]);
  const float* fallback = rgba.pixel(x, y);
  for (int k = 0; k < 4; ++k) out[k] = v[4] > 1e-6f ? v[k] / v[4] : fallback[k];
}

std::vector<Level> planLevels(float max_sigma, const BlurOptions& o) {
  std::vector<Level> levels;
  for (double s = std::max(o.min_sigma, o.first_level);; s *= o.level_ratio) {
    Level l;
    l.sigma = s;
    l.threshold = static_cast<float>(o.halo_ratio * s);
    // Large σ: blur a box-shrunk copy (f ≤ σ/2) and read it back bilinearly; the box and the
    // tent add variance (f² − 1)/12 and f²/6, taken off the blur so the total matches σ².
    while (s / (2 * l.shrink) >= o.shrink_from_sigma / 2.0) l.shrink *= 2;
    if (l.shrink == 1) l.kernel = gaussianKernel(s, l.radius);
    levels.push_back(std::move(l));
    if (s >= max_sigma) break;
  }
  return levels;
}

// Rows [y0, y1) of the output (holding the sharp image there): each pixel blended from its two
// bracketing levels. Each pixel's upper level j (its lower one is j − 1, or the sharp image for
// j = 0) and the weight t of level j that matches its variance, t = (σ² − σ_lo²)/(σ_hi² − σ_lo²),
// come first, with the columns each level is needed in; then level by level, only there.
void blendBand(const ImageF& rgba, const ImageF& sigma_px, const std::vector<Level>& levels,
               double min_sigma, int y0, int y1, ImageF& out) {
  const int w = rgba.width, count = static_cast<int>(levels.size());
  const size_t n = static_cast<size_t>(y1 - y0) * static_cast<size_t>(w);
  std::vector<uint16_t> upper(n, kSharp);
  std::vector<float> weight(n, 0.0f);
  std::vector<int> x_min(static_cast<size_t>(count), w), x_max(static_cast<size_t>(count), -1);
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i =
          static_cast<size_t>(y - y0) * static_cast<size_t>(w) + static_cast<size_t>(x);
      const double s = sigma_px.pixel(x, y)[0];
      if (!(s >= min_sigma)) continue;
      int j = 0;
      while (j < count - 1 && s >= levels[static_cast<size_t>(j)].sigma) ++j;
      const double lo = j > 0 ? levels[static_cast<size_t>(j - 1)].sigma : 0.0,
                   hi = levels[static_cast<size_t>(j)].sigma;
      const double t = std::clamp((s * s - lo * lo) / (hi * hi - lo * lo), 0.0, 1.0);
      upper[i] = static_cast<uint16_t>(j);
      weight[i] = static_cast<float>(t);
      float* o = out.pixel(x, y);
      const float keep = j == 0 ? static_cast<float>(1.0 - t) : 0.0f;  // the sharp image's share
      for (int c = 0; c < 4; ++c) o[c] *= keep;
      for (const int l : {j - 1, j}) {
        if (l < 0) continue;
        x_min[static_cast<size_t>(l)] = std::min(x_min[static_cast<size_t>(l)], x);
        x_max[static_cast<size_t>(l)] = std::max(x_max[static_cast<size_t>(l)], x);
      }
    }
  std::vector<float> scratch, fine;
  for (int l = 0; l < count; ++l) {
    const int xa = x_min[static_cast<size_t>(l)], xb = x_max[static_cast<size_t>(l)] + 1;
    if (xb <= xa) continue;
    const Level& level = levels[static_cast<size_t>(l)];
    if (level.shrink == 1) fineLevelBand(rgba, sigma_px, level, y0, y1, xa, xb, scratch, fine);
    for (int y = y0; y < y1; ++y)
      for (int x = xa; x < xb; ++x) {
        const size_t i =
            static_cast<size_t>(y - y0) * static_cast<size_t>(w) + static_cast<size_t>(x);
        if (upper[i] == kSharp) continue;
        const int j = upper[i];
        float share = 0.0f;
        if (j == l)
          share = weight[i];
        else if (j - 1 == l)
          share = 1.0f - weight[i];
        else
          continue;
        float v[4];
        if (level.shrink == 1) {
          const float* f =
              fine.data() + (static_cast<size_t>(y - y0) * static_cast<size_t>(xb - xa) +
                             static_cast<size_t>(x - xa)) *
                                4;
          std::copy(f, f + 4, v);
        } else {
          coarseLevelAt(rgba, level, x, y, v);
        }
        float* o = out.pixel(x, y);
        for (int c = 0; c < 4; ++c) o[c] += share * v[c];
      }
  }
}

}  // namespace

ImageF stackBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options) {
  checkBlurInputs(rgba, sigma_px);
  if (!(options.level_ratio > 1.0)) throw std::invalid_argument("stack level ratio must exceed 1");
  if (!(options.halo_ratio >= 0.0)) throw std::invalid_argument("halo ratio must be ≥ 0");
  const int h = rgba.height;
  ImageF out = rgba;  // sharp pixels stay as they are
  float max_sigma = 0.0f;
  for (float s : sigma_px.data) max_sigma = std::max(max_sigma, s);
  if (!(max_sigma >= options.min_sigma)) return out;

  std::vector<Level> levels = planLevels(max_sigma, options);
  if (levels.size() >= kSharp) throw std::invalid_argument("depth of field: too many stack levels");
  size_t coarse = 0, coarse_done = 0;
  for (const Level& l : levels) coarse += l.shrink > 1;
  // Progress: the coarse levels take the first third, the output pass the rest.
  const auto report = [&](double fraction) {
    return !options.progress || options.progress(fraction);
  };
  std::vector<Level*> coarse_levels;
  for (Level& l : levels)
    if (l.shrink > 1) coarse_levels.push_back(&l);
  maskedShrinkAll(rgba, sigma_px, coarse_levels, options.threads);
  for (Level* l : coarse_levels) {
    const int f = l->shrink;
    const double extra = (f * f - 1.0) / 12.0 + f * f / 6.0;
    l->blurred = blur5(std::move(l->blurred),
                       std::sqrt(std::max(l->sigma * l->sigma - extra, 0.25)) / f, options.threads);
    if (!report(++coarse_done / (3.0 * static_cast<double>(coarse)))) return {};
  }

  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = 32;
  if (options.progress)
    po.progress = [&](double f) { return options.progress(1.0 / 3.0 + f * 2.0 / 3.0); };
  const bool done = parallelForRows(h, po, [&](int y0, int y1) {
    blendBand(rgba, sigma_px, levels, options.min_sigma, y0, y1, out);
  });
  return done ? out : ImageF{};
}

}  // namespace artcam
