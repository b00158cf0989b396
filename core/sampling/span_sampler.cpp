// SPDX-License-Identifier: Apache-2.0
#include "core/sampling/span_sampler.h"

#include "core/sampling/span_sampler_avx2.h"
#include "core/sampling/span_sampler_avx2_wide.h"
#include "core/sampling/span_sampler_avx512.h"
#include "core/sampling/span_sampler_cubic.h"
#include "core/util/cpu_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace artcam {
namespace {

using Context = SpanSampler::Context;

template <class T>
[[gnu::always_inline]] inline const T* pixelAt(const Context& k, int x, int y, int channels) {
  return static_cast<const T*>(static_cast<const void*>(k.src + y * k.src_row)) + x * channels;
}

// sampling.h's Keys weights (a = −0.5) in float: the taps are float anyway.
inline void cubicWeightsF(float t, float w[4]) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = -0.5f * t3 + t2 - 0.5f * t;
  w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
  w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
  w[3] = 0.5f * t3 - 0.5f * t2;
}

// Each tap returns the coverage and adds weight · value to sum[0 … C). Interior paths skip the
// bounds tests; the border paths keep sampling.h's exact semantics.
template <class T, int C>
[[gnu::always_inline]] inline float nearestTap(const Context& k, float fx, float fy, float* sum) {
  // Extend: the bilinear reach (−1, size) reads the edge pixel, as position_map.h's rule keeps
  // such pixels; truncation towards 0 below already rounds (−1, −½) to pixel 0.
  if (!(fx >= -0.5f && fx < k.width - 0.5f && fy >= -0.5f && fy < k.height - 0.5f) &&
      !(k.extend && fx > -1.0f && fx < k.width && fy > -1.0f && fy < k.height))
    return 0.0f;
  const int x = std::min(static_cast<int>(fx + 0.5f), k.width - 1);
  const int y = std::min(static_cast<int>(fy + 0.5f), k.height - 1);
  const T* p = pixelAt<T>(k, x, y, C);
  for (int c = 0; c < C; ++c) sum[c] += static_cast<float>(p[c]);
  return 1.0f;
}

template <class T, int C>
[[gnu::always_inline]] inline float bilinearTap(const Context& k, float fx, float fy, float* sum) {
  if (!(fx > -1.0f && fx < k.width && fy > -1.0f && fy < k.height)) return 0.0f;
  // floor() without a libm call on the SSE2 baseline: truncation of a positive number.
  const int x0 = static_cast<int>(fx + 1.0f) - 1, y0 = static_cast<int>(fy + 1.0f) - 1;
  const float flx = static_cast<float>(x0), fly = static_cast<float>(y0);
  const float ax = fx - flx, ay = fy - fly;
  const float wx[2] = {1.0f - ax, ax}, wy[2] = {1.0f - ay, ay};
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < k.width && y0 + 1 < k.height) {
    const T* r0 = pixelAt<T>(k, x0, y0, C);
    const T* r1 = pixelAt<T>(k, x0, y0 + 1, C);
    for (int c = 0; c < C; ++c) {
      const float top = wx[0] * static_cast<float>(r0[c]) + wx[1] * static_cast<float>(r0[c + C]);
      const float bottom = wx[0] * static_cast<float>(r1[c]) + wx[1] * static_cast<float>(r1[c + C]);
      sum[c] += wy[0] * top + wy[1] * bottom;
    }
    return 1.0f;
  }
  // The border: taps outside read 0 (transparent), or the nearest edge pixel (extend).
  float coverage = 0.0f;
  for (int j = 0; j < 2; ++j) {
    int y = y0 + j;
    if (y < 0 || y >= k.height) {
      if (!k.extend) continue;
      y = std::clamp(y, 0, k.height - 1);
    }
    for (int i = 0; i < 2; ++i) {
      int x = x0 + i;
      if (x < 0 || x >= k.width) {
        if (!k.extend) continue;
        x = std::clamp(x, 0, k.width - 1);
      }
      const float w = wx[i] * wy[j];
      const T* p = pixelAt<T>(k, x, y, C);
      for (int c = 0; c < C; ++c) sum[c] += w * static_cast<float>(p[c]);
      coverage += w;
    }
  }
  return coverage;
}

template <class T, int C>
[[gnu::always_inline]] inline float bicubicTap(const Context& k, float fx, float fy, float* sum) {
  if (!(fx > -2.0f && fx < k.width + 1.0f && fy > -2.0f && fy < k.height + 1.0f)) return 0.0f;
  const int ix = static_cast<int>(fx + 2.0f) - 2, iy = static_cast<int>(fy + 2.0f) - 2;
  const int x0 = ix - 1, y0 = iy - 1;
  float wx[4], wy[4];
  cubicWeightsF(fx - static_cast<float>(ix), wx);
  cubicWeightsF(fy - static_cast<float>(iy), wy);
  const bool interior = x0 >= 0 && y0 >= 0 && x0 + 3 < k.width && y0 + 3 < k.height;
  if (interior) {
    for (int j = 0; j < 4; ++j) {
      const T* p = pixelAt<T>(k, x0, y0 + j, C);
      for (int c = 0; c < C; ++c)
        sum[c] += wy[j] * (wx[0] * static_cast<float>(p[c]) + wx[1] * static_cast<float>(p[c + C]) +
                           wx[2] * static_cast<float>(p[c + 2 * C]) + wx[3] * static_cast<float>(p[c + 3 * C]));
    }
    return 1.0f;
  }
  float coverage = 0.0f;
  for (int j = 0; j < 4; ++j) {
    int y = y0 + j;
    if (y < 0 || y >= k.height) {
      if (!k.extend) continue;
      y = std::clamp(y, 0, k.height - 1);
    }
    float row[C] = {};
    float row_cover = 0.0f;
    for (int i = 0; i < 4; ++i) {
      int x = x0 + i;
      if (x < 0 || x >= k.width) {
        if (!k.extend) continue;
        x = std::clamp(x, 0, k.width - 1);
      }
      const T* p = pixelAt<T>(k, x, y, C);
      for (int c = 0; c < C; ++c) row[c] += wx[i] * static_cast<float>(p[c]);
      row_cover += wx[i];
    }
    for (int c = 0; c < C; ++c) sum[c] += wy[j] * row[c];
    coverage += wy[j] * row_cover;
  }
  return coverage;
}

template <class T>
[[gnu::always_inline]] inline T store(float v, float full) {
  if constexpr (std::is_floating_point_v<T>) {
    (void)full;
    return v;
  } else {
    return static_cast<T>(std::clamp(v + 0.5f, 0.0f, full));
  }
}

// The 8-bit one-tap paths' interior: both bilinear taps inside (fx, fy = position − ½).
[[gnu::always_inline]] inline bool interiorU8(int w, int h, float fx, float fy) {
  return fx >= 0.0f && fy >= 0.0f && fx < w - 1.0f && fy < h - 1.0f;
}

// The 8-bit bilinear's quantised position (see below): the top-left tap and the weights.
struct BilinearQuanta {
  int x0, y0, ax, ay;
  [[gnu::always_inline]] BilinearQuanta(int w, float fx, float fy) {
    const int qx = static_cast<int>(fx * 256.0f + 0.5f);
    x0 = std::min(qx >> 8, w - 2), y0 = static_cast<int>(fy);  // fy < h − 1
    ax = qx - (x0 << 8);                                         // 0 … 256
    ay = static_cast<int>((fy - static_cast<float>(y0)) * 255.0f + 0.5f);  // 0 … 255
  }
  // One channel: r0, r1 its sample in the tap rows, the right tap `stride` bytes on.
  [[gnu::always_inline]] std::uint8_t blend(const std::uint8_t* r0, const std::uint8_t* r1, int stride) const {
    const int left = (255 - ay) * r0[0] + ay * r1[0];
    const int right = (255 - ay) * r0[stride] + ay * r1[stride];
    return static_cast<std::uint8_t>(((256 - ax) * left + ax * right + 32640) / 65280);
  }
};

// 8-bit nearest and bilinear without leaving integers in the interior (most pixels): nearest
// copies the bytes, bilinear weighs rows by 1/255 and columns by 1/256 (position quanta of
// 1/510 and 1/512 px at worst, sixteen times finer than OpenCV's 1/32), in exact integers:
//   L = (255 − ay) p00 + ay p10, R = (255 − ay) p01 + ay p11,
//   out = ⌊((256 − ax) L + ax R + 32640) / 65280⌋,
// the one rounding at the end; within one code value of the float path. Rows by 255ths, not
// 256ths, so both row weights fit a byte (the AVX2 clone's _mm256_maddubs_epi16) and the lower
// row is always y0 + 1. Border pixels take the float taps and their exact semantics. The AVX2
// clone (span_sampler_avx2.h) computes the same integers.
// A: alpha appended to a source without one (RGB → RGBA previews): 255 inside, the coverage
// at the borders, as sampleSpan's general path.
template <int C, Filter F, bool A = false>
long long sampleSpanU8(const Context& k, std::uint8_t* out, int n, const float* sx, const float* sy,
                       const unsigned char* valid) {
  long long transparent = 0;
  const int w = k.width, h = k.height;
  const int src_alpha = k.src_alpha;
  for (int i = 0; i < n; ++i, out += C + (A ? 1 : 0)) {
    if constexpr (A) out[C] = 255;
    const float fx = sx[i] - 0.5f, fy = sy[i] - 0.5f;
    if constexpr (F == Filter::Nearest) {
      if (valid[i] && interiorU8(w, h, fx, fy)) {
        const std::uint8_t* p = pixelAt<std::uint8_t>(k, static_cast<int>(fx + 0.5f), static_cast<int>(fy + 0.5f), C);
        for (int c = 0; c < C; ++c) out[c] = p[c];
        if (src_alpha >= 0) transparent += out[src_alpha] == 0;
        continue;
      }
    } else {
      if (valid[i] && interiorU8(w, h, fx, fy)) {
        const BilinearQuanta q(w, fx, fy);
        const std::uint8_t* r0 = pixelAt<std::uint8_t>(k, q.x0, q.y0, C);
        const std::uint8_t* r1 = pixelAt<std::uint8_t>(k, q.x0, q.y0 + 1, C);
        for (int c = 0; c < C; ++c) out[c] = q.blend(r0 + c, r1 + c, C);
        if (src_alpha >= 0) transparent += out[src_alpha] == 0;
        continue;
      }
    }
    float sum[C] = {};
    float coverage = 0.0f;
    if (valid[i]) {
      if constexpr (F == Filter::Nearest) coverage = nearestTap<std::uint8_t, C>(k, fx, fy, sum);
      else coverage = bilinearTap<std::uint8_t, C>(k, fx, fy, sum);
    }
    for (int c = 0; c < C; ++c) out[c] = store<std::uint8_t>(sum[c], k.full);
    float alpha = coverage;
    if constexpr (A) {
      alpha = std::clamp(coverage, 0.0f, 1.0f) * k.full;
      out[C] = store<std::uint8_t>(alpha, k.full);
    } else if (src_alpha >= 0) {
      alpha = std::clamp(sum[src_alpha], 0.0f, k.full);
      out[src_alpha] = store<std::uint8_t>(alpha, k.full);
    }
    transparent += alpha <= 0.0f;
  }
  return transparent;
}

// 8-bit bicubic, C = 3 or 4: pixels whose taps are all inside by cubic::interior* (rows first,
// span_sampler_cubic.h; kSimd picks the AVX2 clone, bit-identical), the rest by the general
// float taps. A: alpha appended to RGB (previews): 255 inside, the coverage at the borders.
template <int C, bool A, bool kSimd>
[[gnu::always_inline]] inline long long cubicSpanU8(const Context& k, std::uint8_t* out, int n,
                                                    const float* sx, const float* sy,
                                                    const unsigned char* valid) {
  long long transparent = 0;
  for (int i = 0; i < n; ++i, out += C + (A ? 1 : 0)) {
    const float fx = sx[i] - 0.5f, fy = sy[i] - 0.5f;
    cubic::CubicInterior p;
    if (valid[i] && p.fits<C>(k, fx, fy)) {
      float alpha = 1.0f;
#ifdef ARTCAM_HAVE_AVX2_CUBIC
      if constexpr (kSimd) {
        alpha = cubic::interiorAvx2<C, A>(k, p, out, i + 1 < n);
      } else
#endif
      {
        float v[4];
        cubic::interiorScalar<C>(k, p, v);
        for (int c = 0; c < C; ++c) out[c] = store<std::uint8_t>(v[c], k.full);
        if constexpr (A) out[C] = 255;
        if (k.src_alpha >= 0) alpha = v[k.src_alpha];
      }
      if constexpr (!A)
        if (k.src_alpha >= 0) transparent += !(std::clamp(alpha, 0.0f, k.full) > 0.0f);
      continue;
    }
    float sum[C] = {};
    const float coverage = valid[i] ? bicubicTap<std::uint8_t, C>(k, fx, fy, sum) : 0.0f;
    for (int c = 0; c < C; ++c) out[c] = store<std::uint8_t>(sum[c], k.full);
    float alpha = coverage;
    if constexpr (A) {
      alpha = std::clamp(coverage, 0.0f, 1.0f) * k.full;
      out[C] = store<std::uint8_t>(alpha, k.full);
    } else if (k.src_alpha >= 0) {
      alpha = std::clamp(sum[k.src_alpha], 0.0f, k.full);
      out[k.src_alpha] = store<std::uint8_t>(alpha, k.full);
    }
    transparent += alpha <= 0.0f;
  }
  return transparent;
}

template <class T, int C, Filter F>
long long sampleSpan(const Context& k, unsigned char* out_bytes, int n, const float* sx,
                     const float* sy, const unsigned char* valid, int supersample,
                     const float* jac) {
  T* out = static_cast<T*>(static_cast<void*>(out_bytes));
  const int oc = k.out_channels;
  long long transparent = 0;
  const auto tapAt = [&k](float fx, float fy, float* sum) __attribute__((always_inline)) {
    if constexpr (F == Filter::Nearest) return nearestTap<T, C>(k, fx, fy, sum);
    else if constexpr (F == Filter::Bilinear) return bilinearTap<T, C>(k, fx, fy, sum);
    else return bicubicTap<T, C>(k, fx, fy, sum);
  };
  if constexpr (std::is_same_v<T, std::uint8_t> && F != Filter::Bicubic) {
    if (supersample <= 1 && oc == C) return sampleSpanU8<C, F>(k, out, n, sx, sy, valid);
    if (supersample <= 1 && k.append_alpha && oc == C + 1) return sampleSpanU8<C, F, true>(k, out, n, sx, sy, valid);
  }
  if constexpr (std::is_same_v<T, std::uint8_t> && F == Filter::Bicubic && (C == 3 || C == 4)) {
    if (supersample <= 1 && oc == C) return cubicSpanU8<C, false, false>(k, out, n, sx, sy, valid);
    if constexpr (C == 3)
      if (supersample <= 1 && k.append_alpha && oc == C + 1) return cubicSpanU8<3, true, false>(k, out, n, sx, sy, valid);
  }
  if (supersample <= 1 && oc == C) {
    // The common case (one tap, output channels = source channels): no alpha bookkeeping
    // beyond the source's own, nothing the compiler cannot keep in registers.
    const float full = k.full;
    const int src_alpha = k.src_alpha;
    for (int i = 0; i < n; ++i, out += C) {
      float sum[C] = {};
      const float coverage = valid[i] ? tapAt(sx[i] - 0.5f, sy[i] - 0.5f, sum) : 0.0f;
      for (int c = 0; c < C; ++c) out[c] = store<T>(sum[c], full);
      float alpha = coverage;
      if (src_alpha >= 0) {
        alpha = std::clamp(sum[src_alpha], 0.0f, full);
        out[src_alpha] = store<T>(alpha, full);
      }
      transparent += alpha <= 0.0f;
    }
    return transparent;
  }
  const float inv_count = 1.0f / static_cast<float>(supersample * supersample);
  for (int i = 0; i < n; ++i, out += oc) {
    if (!valid[i]) {
      std::fill(out, out + oc, T(0));
      ++transparent;
      continue;
    }
    float sum[C] = {};
    float coverage = 0.0f;
    const auto tap = [&](float fx, float fy) __attribute__((always_inline)) { coverage += tapAt(fx, fy, sum); };
    const float fx = sx[i] - 0.5f, fy = sy[i] - 0.5f;
    if (supersample <= 1) {
      tap(fx, fy);
    } else {
      for (int b = 0; b < supersample; ++b) {
        const float dy = (b + 0.5f) / supersample - 0.5f;
        for (int a = 0; a < supersample; ++a) {
          const float dx = (a + 0.5f) / supersample - 0.5f;
          tap(fx + jac[0] * dx + jac[1] * dy, fy + jac[2] * dx + jac[3] * dy);
        }
      }
      for (int c = 0; c < C; ++c) sum[c] *= inv_count;
      coverage *= inv_count;
    }
    for (int c = 0; c < C; ++c) out[c] = store<T>(sum[c], k.full);
    float alpha = coverage;
    if (k.append_alpha) {
      alpha = std::clamp(coverage, 0.0f, 1.0f) * k.full;
      out[k.out_alpha] = store<T>(alpha, k.full);
    } else if (k.src_alpha >= 0) {
      alpha = std::clamp(sum[k.src_alpha], 0.0f, k.full);
      out[k.src_alpha] = store<T>(alpha, k.full);
    }
    if (alpha <= 0.0f) ++transparent;
  }
  return transparent;
}

#ifdef ARTCAM_HAVE_AVX2_SAMPLER
// The AVX2 clone of the 8-bit one-tap paths (span_sampler_avx2.h); everything else, and every
// group of eight that touches a border, runs the scalar code above.
template <int C, Filter F>
long long sampleSpanU8Simd(const Context& k, unsigned char* out_bytes, int n, const float* sx,
                           const float* sy, const unsigned char* valid, int supersample,
                           const float* jac) {
  if (supersample > 1) return sampleSpan<std::uint8_t, C, F>(k, out_bytes, n, sx, sy, valid, supersample, jac);
  std::uint8_t* out = out_bytes;
  if constexpr (C == 3) {
    if (k.append_alpha) {
      // RGB → RGBA (previews): alpha 255 inside, the coverage at the borders.
      if constexpr (F == Filter::Bilinear)
        return avx2::bilinearU8<3, true>(k, out, n, sx, sy, valid, &sampleSpanU8<3, F, true>);
      else return avx2::nearestU8<3, true>(k, out, n, sx, sy, valid, &sampleSpanU8<3, F, true>);
    }
  }
  if (k.out_channels != C) return sampleSpan<std::uint8_t, C, F>(k, out_bytes, n, sx, sy, valid, supersample, jac);
  if constexpr (F == Filter::Bilinear) return avx2::bilinearU8<C>(k, out, n, sx, sy, valid, &sampleSpanU8<C, F>);
  else return avx2::nearestU8<C>(k, out, n, sx, sy, valid, &sampleSpanU8<C, F>);
}

// The AVX2 clone of the 16-bit and float one-tap nearest and bilinear paths
// (span_sampler_avx2_wide.h); supersampling and every group it does not take run the scalar
// code above.
template <class T, int C, Filter F>
long long sampleSpanWideSimd(const Context& k, unsigned char* out, int n, const float* sx, const float* sy,
                             const unsigned char* valid, int supersample, const float* jac) {
  if (supersample <= 1) {
    if (k.out_channels == C) return avx2::sampleWide<T, C, F>(k, out, n, sx, sy, valid, &sampleSpan<T, C, F>);
    if constexpr (C == 3)
      if (k.append_alpha) return avx2::sampleWide<T, 3, F, true>(k, out, n, sx, sy, valid, &sampleSpan<T, C, F>);
  }
  return sampleSpan<T, C, F>(k, out, n, sx, sy, valid, supersample, jac);
}

template <class T>
SpanSampler::SpanFn pickWide(Filter filter, int channels) {
  if (filter == Filter::Bilinear)
    return channels == 3 ? sampleSpanWideSimd<T, 3, Filter::Bilinear> : sampleSpanWideSimd<T, 4, Filter::Bilinear>;
  return channels == 3 ? sampleSpanWideSimd<T, 3, Filter::Nearest> : sampleSpanWideSimd<T, 4, Filter::Nearest>;
}

// The AVX2 clone of the 8-bit bicubic (span_sampler_cubic.h): the interior pixels by
// cubic::interiorAvx2, everything else as the scalar code.
template <int C>
__attribute__((target("avx2"))) long long cubicSpanU8Simd(const Context& k, unsigned char* out, int n,
                                                         const float* sx, const float* sy,
                                                         const unsigned char* valid, int supersample,
                                                         const float* jac) {
  if (supersample <= 1 && k.out_channels == C) return cubicSpanU8<C, false, true>(k, out, n, sx, sy, valid);
  if constexpr (C == 3)
    if (supersample <= 1 && k.append_alpha && k.out_channels == 4) return cubicSpanU8<3, true, true>(k, out, n, sx, sy, valid);
  return sampleSpan<std::uint8_t, C, Filter::Bicubic>(k, out, n, sx, sy, valid, supersample, jac);
}

#ifdef ARTCAM_HAVE_AVX512_SAMPLER
// The AVX-512 bilinear (span_sampler_avx512.h) for RGB8 → RGB8 without alpha (the photo
// case) and RGB8 → RGBA8 with alpha appended (the render front door and the studio); every
// other layout, and every group it cannot take, runs the AVX2 clone.
long long bilinearRgb8Avx512(const Context& k, unsigned char* out, int n, const float* sx,
                             const float* sy, const unsigned char* valid, int supersample,
                             const float* jac) {
  // A 3-channel source writes 3 channels, or 4 with alpha appended (SpanSampler's checks).
  if (supersample > 1 || k.src_alpha >= 0)
    return sampleSpanU8Simd<3, Filter::Bilinear>(k, out, n, sx, sy, valid, supersample, jac);
  if (k.append_alpha)
    return avx512::bilinearRgb8<true>(k, out, n, sx, sy, valid, &sampleSpanU8<3, Filter::Bilinear, true>);
  return avx512::bilinearRgb8(k, out, n, sx, sy, valid, &sampleSpanU8<3, Filter::Bilinear>);
}

// The AVX-512 16-bit and float bilinear (span_sampler_avx512.h) for RGB → RGB without alpha;
// every other layout, and every group it cannot take, runs the AVX2 clone.
template <class T>
long long bilinearWideRgbAvx512(const Context& k, unsigned char* out, int n, const float* sx,
                                const float* sy, const unsigned char* valid, int supersample,
                                const float* jac) {
  if (supersample > 1 || k.append_alpha || k.src_alpha >= 0)
    return sampleSpanWideSimd<T, 3, Filter::Bilinear>(k, out, n, sx, sy, valid, supersample, jac);
  return avx512::bilinearWideRgb<T>(k, out, n, sx, sy, valid, &sampleSpanWideSimd<T, 3, Filter::Bilinear>);
}

bool cpuHasAvx512Sampler() { return cpuHasAvx512bwvl() && __builtin_cpu_supports("avx512vbmi"); }
#endif

// AVX2 when the CPU has it and the source's byte offsets fit the 32-bit offsets; AVX-512 for
// RGB8 bilinear where the CPU has it and rows hold a 64-byte window. 16-bit and float: AVX2
// nearest and bilinear (their bicubic stays scalar), AVX-512 for RGB bilinear.
SpanSampler::SpanFn pickSimd(const ConstImageView& src, Filter filter, bool allow_avx512) {
  if (src.channels != 3 && src.channels != 4) return nullptr;
  if (!cpuHasAvx2()) return nullptr;
  if (src.type != PixelType::UInt8) {
    if (filter == Filter::Bicubic) return nullptr;
    if (src.row_bytes <= 0 || static_cast<double>(src.row_bytes) * src.height > 2147483647.0 - 64.0) return nullptr;
#ifdef ARTCAM_HAVE_AVX512_SAMPLER
    if (filter == Filter::Bilinear && src.channels == 3 && allow_avx512 && cpuHasAvx512Sampler())
      return src.type == PixelType::UInt16 ? bilinearWideRgbAvx512<std::uint16_t> : bilinearWideRgbAvx512<float>;
#endif
    return src.type == PixelType::UInt16 ? pickWide<std::uint16_t>(filter, src.channels) : pickWide<float>(filter, src.channels);
  }
  if (filter == Filter::Bicubic) return src.channels == 3 ? cubicSpanU8Simd<3> : cubicSpanU8Simd<4>;
  if (src.row_bytes <= 0 || static_cast<double>(src.row_bytes) * src.height > 2147483647.0 - 64.0) return nullptr;
#ifdef ARTCAM_HAVE_AVX512_SAMPLER
  if (filter == Filter::Bilinear && src.channels == 3 && allow_avx512 && src.row_bytes >= 64 && cpuHasAvx512Sampler())
    return bilinearRgb8Avx512;
#endif
  if (filter == Filter::Bilinear)
    return src.channels == 3 ? sampleSpanU8Simd<3, Filter::Bilinear> : sampleSpanU8Simd<4, Filter::Bilinear>;
  return src.channels == 3 ? sampleSpanU8Simd<3, Filter::Nearest> : sampleSpanU8Simd<4, Filter::Nearest>;
}
#else
SpanSampler::SpanFn pickSimd(const ConstImageView&, Filter, bool) { return nullptr; }
#endif

template <class T, Filter F>
SpanSampler::SpanFn pickChannels(int channels) {
  switch (channels) {
    case 1: return sampleSpan<T, 1, F>;
    case 2: return sampleSpan<T, 2, F>;
    case 3: return sampleSpan<T, 3, F>;
    default: return sampleSpan<T, 4, F>;
  }
}

template <class T>
SpanSampler::SpanFn pickFilter(Filter filter, int channels) {
  switch (filter) {
    case Filter::Nearest: return pickChannels<T, Filter::Nearest>(channels);
    case Filter::Bilinear: return pickChannels<T, Filter::Bilinear>(channels);
    case Filter::Bicubic: break;
  }
  return pickChannels<T, Filter::Bicubic>(channels);
}

}  // namespace

SpanSampler::SpanSampler(const ConstImageView& src, const ImageView& dst, Filter filter,
                         bool allow_simd, bool allow_avx512, EdgeMode edge)
    : dst_(dst) {
  if (src.empty() || src.channels < 1 || src.channels > 4)
    throw std::invalid_argument("the source image is empty or has more than 4 channels");
  if (src.alpha_channel >= src.channels)
    throw std::invalid_argument("the source image's alpha channel index is out of range");
  if (dst.empty() || dst.type != src.type)
    throw std::invalid_argument("the output image is empty or its pixel type differs from the source's");
  const bool append = src.alpha_channel < 0 && dst.channels == src.channels + 1;
  if (!append && dst.channels != src.channels)
    throw std::invalid_argument("the output must have the source's channels, or one more for alpha");
  if (append && dst.alpha_channel != src.channels)
    throw std::invalid_argument("an appended alpha channel must be the output's last channel");
  context_.src = static_cast<const unsigned char*>(src.data);
  context_.src_row = src.row_bytes;
  context_.width = src.width;
  context_.height = src.height;
  context_.src_alpha = src.alpha_channel;
  context_.out_channels = dst.channels;
  context_.append_alpha = append;
  context_.out_alpha = append ? src.channels : src.alpha_channel;
  context_.full = pixelTypeFullScale(src.type);
  context_.extend = edge == EdgeMode::Extend;
  filter_ = filter;
  u8_ = src.type == PixelType::UInt8;
  switch (src.type) {
    case PixelType::UInt8: fn_ = pickFilter<std::uint8_t>(filter, src.channels); break;
    case PixelType::UInt16: fn_ = pickFilter<std::uint16_t>(filter, src.channels); break;
    case PixelType::Float: fn_ = pickFilter<float>(filter, src.channels); break;
  }
  if (allow_simd)
    if (const SpanFn simd = pickSimd(src, filter, allow_avx512)) {
      fn_ = simd;
      simd_ = true;
#ifdef ARTCAM_HAVE_AVX512_SAMPLER
      avx512_ = simd == bilinearRgb8Avx512 || simd == bilinearWideRgbAvx512<std::uint16_t> ||
                simd == bilinearWideRgbAvx512<float>;
#endif
    }
}

long long SpanSampler::run(int y, int x0, int n, const float* sx, const float* sy,
                           const unsigned char* valid, int supersample, const float* jacobian) const {
  unsigned char* out = static_cast<unsigned char*>(dst_.row(y)) +
                       static_cast<std::ptrdiff_t>(x0) * dst_.pixelBytes();
  return fn_(context_, out, n, sx, sy, valid, supersample, jacobian);
}

int SpanSampler::runChannelsInterior(int y, int x0, int n, int count, const float* const* sx,
                                     const float* const* sy, const unsigned char* const* valid,
                                     const ChannelShift* shift, long long* transparent,
                                     unsigned char* out_at) const {
  const Context& k = context_;
  if (!u8_ || filter_ == Filter::Bicubic || !k.append_alpha || count < 1 || count > k.out_channels - 1) return -1;
  const int w = k.width, h = k.height;
  const int stride = k.out_channels, src_channels = stride - 1;
  std::uint8_t* out = out_at ? out_at : static_cast<std::uint8_t*>(dst_.row(y)) + static_cast<std::ptrdiff_t>(x0) * stride;
  int done = 0;
#ifdef ARTCAM_HAVE_AVX2_SAMPLER
  if (simd_ && filter_ == Filter::Bilinear && src_channels == 3 && count == 3) {
    const int groups = n & ~7;
    // A whole-pixel shift's channel at pixel i is the source's at (x0 + dx + i, y + dy): the
    // interior test (0 ≤ f < size − 1, f = position − ½) once for the span's vector part.
    const std::uint8_t* direct[3] = {nullptr, nullptr, nullptr};
    for (int c = 0; shift && c < 3; ++c) {
      const int sx0 = x0 + shift[c].dx, sy0 = y + shift[c].dy;
      if (shift[c].whole && sx0 >= 0 && sx0 + groups - 1 < w - 1 && sy0 >= 0 && sy0 < h - 1)
        direct[c] = k.src + static_cast<std::ptrdiff_t>(sy0) * k.src_row + 3 * static_cast<std::ptrdiff_t>(sx0) + c;
    }
    long long zeros = 0;
#ifdef ARTCAM_HAVE_AVX512_SAMPLER
    if (avx512_) done = avx512::bilinearChannelsRgb8(k, out, groups, sx, sy, valid, direct, zeros);
    else
#endif
      done = avx2::bilinearChannelsRgb8(k, out, groups, sx, sy, valid, direct, zeros);
    if (transparent) *transparent += zeros;
    if (done < groups) return done;
  }
#endif
  // interiorU8 without branches per pixel: the pixels up to the first that is not interior.
  const float x_end = w - 1.0f, y_end = h - 1.0f;
  int stop = done;
  while (stop < n) {
    bool inside = true;
    for (int j = 0; j < count; ++j) {
      const float fx = sx[j][stop] - 0.5f, fy = sy[j][stop] - 0.5f;
      inside &= (valid[j][stop] != 0) & (fx >= 0.0f) & (fy >= 0.0f) & (fx < x_end) & (fy < y_end);
    }
    if (!inside) break;
    ++stop;
  }
  for (int i = done; i < stop; ++i) out[static_cast<std::ptrdiff_t>(i) * stride + stride - 1] = 255;
  for (int c = 0; c < src_channels; ++c) {
    const int j = c < count ? c : 0;
    const std::uint8_t* src = k.src + c;
    std::uint8_t* o = out + static_cast<std::ptrdiff_t>(done) * stride + c;
    for (int i = done; i < stop; ++i, o += stride) {
      const float fx = sx[j][i] - 0.5f, fy = sy[j][i] - 0.5f;
      if (filter_ == Filter::Nearest) {  // run()'s rounding, to the same tap
        *o = src[static_cast<int>(fy + 0.5f) * k.src_row + static_cast<int>(fx + 0.5f) * src_channels];
      } else {
        const BilinearQuanta q(w, fx, fy);
        const std::uint8_t* r0 = src + q.y0 * k.src_row + q.x0 * src_channels;
        *o = q.blend(r0, r0 + k.src_row, src_channels);
      }
    }
  }
  return stop;
}

}  // namespace artcam
