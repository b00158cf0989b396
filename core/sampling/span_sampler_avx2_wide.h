// SPDX-License-Identifier: Apache-2.0
// AVX2 kernels of the 16-bit and float sampler's one-tap paths (span_sampler.cpp only).
//
// Runtime dispatch only, as span_sampler_avx2.h: target("avx2") and nothing more. Not "fma":
// these kernels must round exactly as the scalar sampleSpan<T, C, F> compiled for the x86-64
// baseline, which has no FMA, so every a · b + c here is a multiply and an add, in the scalar
// order. (The project sets no -ffp-contract; with FMA out of the target set there is nothing to
// contract into.) They are bit-identical to the scalar code, so the tests demand equality:
// - bilinear: x0 = (int)(fx + 1) − 1, ax = fx − x0, weights (1 − ax, ax), top and bottom
//   rows by columns first, then wy0 · top + wy1 · bottom added to a sum that starts at 0.0f
//   (which turns −0 into +0 for float sources);
// - nearest: the tap min((int)(fx + ½), w − 1), added to 0.0f likewise;
// - stored as store<T> stores: 16-bit (uint16)clamp(v + ½, 0, 65535), float as is; a source
//   alpha clamped to [0, full] and counted transparent when ≤ 0; an alpha appended to RGB is
//   full inside.
// A group of eight with any pixel that is not interior in the scalar code's own terms (the
// integer taps, not the float position: fx + 1 can round up a column), not valid, or whose
// loads would run past the image's last byte goes to the scalar routine, which owns the
// border semantics.
//
// Layout: pixels k and k + 4 of a group share a 256-bit register, one per 128-bit lane with
// its channels in floats (RGB: a fourth, ignored, lane holds the next sample), so each pixel's
// weights are an in-lane broadcast of its element of the eight-lane weight vector (no lane
// crossing), and the arithmetic is the scalar code's per channel. Each tap is one unaligned
// load per pixel (16-bit: 8 bytes, widened; float: 16 bytes), at general-register offsets
// (toRegisters): vpgatherdd is slower here, as for the 8-bit sampler.
#pragma once

#include "core/sampling/span_sampler_avx2.h"

#ifdef ARTCAM_HAVE_AVX2_SAMPLER

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace artcam::avx2 {

template <class P>
[[gnu::always_inline]] inline const P* bytesAs(const unsigned char* p) {
  return static_cast<const P*>(static_cast<const void*>(p));
}
template <class P>
[[gnu::always_inline]] inline P* bytesAs(unsigned char* p) {
  return static_cast<P*>(static_cast<void*>(p));
}

// Four samples at a (low lane) and four at b (high lane), as floats: the pixel's channels and,
// for RGB, the next sample. Reads 4 · sizeof(T) bytes at each.
template <class T>
__attribute__((target("avx2"), always_inline)) inline __m256 loadPair(const unsigned char* a, const unsigned char* b) {
  if constexpr (std::is_same_v<T, float>) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(bytesAs<float>(a))), _mm_loadu_ps(bytesAs<float>(b)), 1);
  } else {
    static_assert(std::is_same_v<T, std::uint16_t>);
    const __m128i lo = _mm_loadl_epi64(bytesAs<__m128i>(a));
    const __m128i both = _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(lo), bytesAs<double>(b)));
    return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(both));
  }
}

// Element P of each lane in all four of that lane's elements: pixel P's value in the low lane,
// pixel P + 4's in the high one.
template <int P>
__attribute__((target("avx2"), always_inline)) inline __m256 lanesOf(__m256 v) {
  return _mm256_permute_ps(v, P * 0x55);
}

// The eight pixels of a group, as four registers of pixel pairs (k, k + 4), written as T.
// Nothing past the group's kOut · 8 samples is written; overlapping stores go in increasing
// address order so each pixel's spare fourth sample is overwritten by the next pixel.
template <class T, int kOut>
__attribute__((target("avx2"), always_inline)) inline void storeGroup(unsigned char* o, const __m256 r[4]) {
  if constexpr (std::is_same_v<T, float>) {
    if constexpr (kOut == 4) {
      _mm256_storeu_ps(bytesAs<float>(o), _mm256_permute2f128_ps(r[0], r[1], 0x20));
      _mm256_storeu_ps(bytesAs<float>(o + 32), _mm256_permute2f128_ps(r[2], r[3], 0x20));
      _mm256_storeu_ps(bytesAs<float>(o + 64), _mm256_permute2f128_ps(r[0], r[1], 0x31));
      _mm256_storeu_ps(bytesAs<float>(o + 96), _mm256_permute2f128_ps(r[2], r[3], 0x31));
    } else {
      for (int p = 0; p < 4; ++p) _mm_storeu_ps(bytesAs<float>(o + 12 * p), _mm256_castps256_ps128(r[p]));
      for (int p = 0; p < 3; ++p) _mm_storeu_ps(bytesAs<float>(o + 48 + 12 * p), _mm256_extractf128_ps(r[p], 1));
      const __m128 last = _mm256_extractf128_ps(r[3], 1);
      _mm_storel_pi(bytesAs<__m64>(o + 84), last);
      _mm_store_ss(bytesAs<float>(o + 92), _mm_movehl_ps(last, last));
    }
  } else {
    // Every value is in [0, 65535] already (clamped as floats), so the saturating pack is exact.
    const __m256i a = _mm256_packus_epi32(_mm256_cvttps_epi32(r[0]), _mm256_cvttps_epi32(r[1]));  // 0 1 | 4 5
    const __m256i b = _mm256_packus_epi32(_mm256_cvttps_epi32(r[2]), _mm256_cvttps_epi32(r[3]));  // 2 3 | 6 7
    const __m256i first = _mm256_permute2x128_si256(a, b, 0x20), second = _mm256_permute2x128_si256(a, b, 0x31);
    if constexpr (kOut == 4) {
      _mm256_storeu_si256(bytesAs<__m256i>(o), first);
      _mm256_storeu_si256(bytesAs<__m256i>(o + 32), second);
    } else {
      // Two pixels of four samples per lane → their six samples, 12 bytes.
      const __m256i squeeze = _mm256_broadcastsi128_si256(
          _mm_setr_epi8(0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13, -1, -1, -1, -1));
      const __m256i f = _mm256_shuffle_epi8(first, squeeze), s = _mm256_shuffle_epi8(second, squeeze);
      _mm_storeu_si128(bytesAs<__m128i>(o), _mm256_castsi256_si128(f));
      _mm_storeu_si128(bytesAs<__m128i>(o + 12), _mm256_extracti128_si256(f, 1));
      _mm_storeu_si128(bytesAs<__m128i>(o + 24), _mm256_castsi256_si128(s));
      const __m128i last = _mm256_extracti128_si256(s, 1);
      _mm_storel_epi64(bytesAs<__m128i>(o + 36), last);
      const std::uint32_t tail = static_cast<std::uint32_t>(_mm_extract_epi32(last, 2));
      std::memcpy(o + 44, &tail, 4);
    }
  }
}

// One group's taps and weights; pixels<…, P>() samples pixels P and P + 4 (one per lane) and
// returns them ready to store: floats with a source alpha clamped, or 16-bit values clamped
// and offset by ½ for the truncation; adds the transparent ones (source alpha ≤ 0) to
// `transparent`.
struct WideGroup {
  const unsigned char* src;
  std::ptrdiff_t below;  // bytes to the next row
  Offsets8 at;           // each pixel's (first) tap
  __m256 wx0, wx1, wy0, wy1;

  template <class T, int C, Filter F, bool kAppendAlpha, int P>
  __attribute__((target("avx2"), always_inline)) __m256 pixels(float full_scale, __m256 alpha_lanes, int alpha_bits,
                                                               long long& transparent) const {
    constexpr int kPixel = C * static_cast<int>(sizeof(T));
    const __m256 zero = _mm256_setzero_ps(), full = _mm256_set1_ps(full_scale);
    const unsigned char* a = src + at[P];
    const unsigned char* b = src + at[P + 4];
    __m256 sum;
    if constexpr (F == Filter::Bilinear) {
      const __m256 bx0 = lanesOf<P>(wx0), bx1 = lanesOf<P>(wx1);
      const __m256 top = _mm256_add_ps(_mm256_mul_ps(bx0, loadPair<T>(a, b)),
                                       _mm256_mul_ps(bx1, loadPair<T>(a + kPixel, b + kPixel)));
      const __m256 bottom = _mm256_add_ps(_mm256_mul_ps(bx0, loadPair<T>(a + below, b + below)),
                                          _mm256_mul_ps(bx1, loadPair<T>(a + below + kPixel, b + below + kPixel)));
      sum = _mm256_add_ps(zero, _mm256_add_ps(_mm256_mul_ps(lanesOf<P>(wy0), top), _mm256_mul_ps(lanesOf<P>(wy1), bottom)));
    } else {
      sum = _mm256_add_ps(zero, loadPair<T>(a, b));
    }
    if (alpha_bits)
      transparent += __builtin_popcount(static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(sum, zero, _CMP_LE_OQ))) &
                                        static_cast<unsigned>(alpha_bits));
    if constexpr (kAppendAlpha) sum = _mm256_blend_ps(sum, full, 0x88);
    if constexpr (std::is_same_v<T, float>) {
      // The alpha clamp as std::clamp: max(0, v) and min(full, v), in that operand order,
      // keep a NaN as the scalar comparisons do.
      return _mm256_blendv_ps(sum, _mm256_min_ps(full, _mm256_max_ps(zero, sum)), alpha_lanes);
    } else {
      return _mm256_min_ps(full, _mm256_max_ps(zero, _mm256_add_ps(sum, _mm256_set1_ps(0.5f))));
    }
  }
};

// Nearest or bilinear, T = uint16_t or float, C = 3 or 4 interleaved channels, output channels
// = C, or (kAppendAlpha, C = 3) RGB → RGBA with alpha full inside. `scalar` is the scalar
// sampleSpan<T, C, F> for the groups this does not take and the tail.
template <class T, int C, Filter F, bool kAppendAlpha = false>
__attribute__((target("avx2"))) long long sampleWide(const SpanSampler::Context& k, unsigned char* out, int n,
                                                     const float* sx, const float* sy, const unsigned char* valid,
                                                     SpanSampler::SpanFn scalar) {
  static_assert(C == 3 || C == 4);
  static_assert(!kAppendAlpha || C == 3);
  static_assert(F == Filter::Nearest || F == Filter::Bilinear);
  constexpr int kPixel = C * static_cast<int>(sizeof(T));
  constexpr int kOutPixel = (kAppendAlpha ? 4 : C) * static_cast<int>(sizeof(T));
  constexpr int kLoad = 4 * static_cast<int>(sizeof(T));  // bytes loadPair reads at a tap
  const __m256 half = _mm256_set1_ps(0.5f), one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  const __m256i row = _mm256_set1_epi32(static_cast<int>(k.src_row));
  const __m256i pixel_bytes = _mm256_set1_epi32(kPixel);
  const __m256i minus_one = _mm256_set1_epi32(-1);
  const __m256i x_last = _mm256_set1_epi32(k.width - 1), y_last = _mm256_set1_epi32(k.height - 1);
  // The image's last byte + 1 as an offset from its first (row padding after the last pixel of
  // the last row is not ours to read). RGB loads read one sample past their pixel, so the taps
  // whose loads reach past it (the last row's last pixel) are left to the scalar code; the
  // offsets fit 32 bits (span_sampler.cpp's pickSimd).
  const std::int64_t end = static_cast<std::int64_t>(k.height - 1) * k.src_row + static_cast<std::int64_t>(k.width) * kPixel;
  // The highest byte offset of a group pixel's first tap that keeps its last load in the image:
  // bilinear's last tap is one row and one pixel on.
  const std::int64_t last_start = end - kLoad - (F == Filter::Bilinear ? k.src_row + kPixel : 0);
  const __m256i start_limit = _mm256_set1_epi32(static_cast<int>(last_start + 1));
  // Nearest's interior: nearestTap's own test.
  const __m256 near_lo = _mm256_set1_ps(-0.5f);
  const __m256 near_xhi = _mm256_set1_ps(static_cast<float>(k.width) - 0.5f);
  const __m256 near_yhi = _mm256_set1_ps(static_cast<float>(k.height) - 0.5f);
  // The source alpha's element in each lane (none: 0), for the clamp and the transparent count.
  const bool has_alpha = !kAppendAlpha && k.src_alpha >= 0;
  const int alpha_bits = has_alpha ? (0x11 << k.src_alpha) : 0;
  const __m256 alpha_lanes = _mm256_castsi256_ps(_mm256_cmpeq_epi32(
      _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3), _mm256_set1_epi32(has_alpha ? k.src_alpha : -1)));
  const unsigned char* src = k.src;
  const std::ptrdiff_t below = k.src_row;
  long long transparent = 0;
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    unsigned char* o = out + static_cast<std::ptrdiff_t>(i) * kOutPixel;
    const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx + i), half);
    const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy + i), half);
    std::uint64_t v;
    std::memcpy(&v, valid + i, 8);
    __m256i off;
    __m256 wx0 = zero, wx1 = zero, wy0 = zero, wy1 = zero;
    bool inside;
    if constexpr (F == Filter::Bilinear) {
      const auto [x0, y0] = tapFloor(fx, fy);
      const __m256i in = _mm256_and_si256(
          _mm256_and_si256(_mm256_cmpgt_epi32(x0, minus_one), _mm256_cmpgt_epi32(x_last, x0)),
          _mm256_and_si256(_mm256_cmpgt_epi32(y0, minus_one), _mm256_cmpgt_epi32(y_last, y0)));
      off = _mm256_add_epi32(_mm256_mullo_epi32(y0, row), _mm256_mullo_epi32(x0, pixel_bytes));
      const __m256i fits = C == 3 ? _mm256_and_si256(in, _mm256_cmpgt_epi32(start_limit, off)) : in;
      inside = v == 0x0101010101010101ull && _mm256_movemask_epi8(fits) == -1;
      if (!inside) {
        if (allOutside(fx, fy, k, valid + i)) {
          // No tap inside (or no preimage) anywhere in the group: the scalar code's zeros,
          // transparent, in every layout and type (+0.0f is all zero bytes).
          std::memset(o, 0, 8 * kOutPixel);
          transparent += 8;
        } else {
          transparent += scalar(k, o, 8, sx + i, sy + i, valid + i, 1, nullptr);
        }
        continue;
      }
      wx1 = _mm256_sub_ps(fx, _mm256_cvtepi32_ps(x0));
      wy1 = _mm256_sub_ps(fy, _mm256_cvtepi32_ps(y0));
      wx0 = _mm256_sub_ps(one, wx1);
      wy0 = _mm256_sub_ps(one, wy1);
    } else {
      const __m256 in = _mm256_and_ps(
          _mm256_and_ps(_mm256_cmp_ps(fx, near_lo, _CMP_GE_OQ), _mm256_cmp_ps(fx, near_xhi, _CMP_LT_OQ)),
          _mm256_and_ps(_mm256_cmp_ps(fy, near_lo, _CMP_GE_OQ), _mm256_cmp_ps(fy, near_yhi, _CMP_LT_OQ)));
      const __m256i x = _mm256_min_epi32(_mm256_cvttps_epi32(_mm256_add_ps(fx, half)), x_last);
      const __m256i y = _mm256_min_epi32(_mm256_cvttps_epi32(_mm256_add_ps(fy, half)), y_last);
      off = _mm256_add_epi32(_mm256_mullo_epi32(y, row), _mm256_mullo_epi32(x, pixel_bytes));
      const __m256 fits = C == 3 ? _mm256_and_ps(in, _mm256_castsi256_ps(_mm256_cmpgt_epi32(start_limit, off))) : in;
      inside = v == 0x0101010101010101ull && _mm256_movemask_ps(fits) == 0xFF;
      if (!inside) {
        transparent += scalar(k, o, 8, sx + i, sy + i, valid + i, 1, nullptr);
        continue;
      }
    }
    const Offsets8 at = toRegisters(off);
    prefetchRowsAhead(k, src + at[0], F == Filter::Bilinear ? 2 * kPixel : kPixel);
    const WideGroup g{src, below, at, wx0, wx1, wy0, wy1};
    __m256 r[4];
    r[0] = g.pixels<T, C, F, kAppendAlpha, 0>(k.full, alpha_lanes, alpha_bits, transparent);
    r[1] = g.pixels<T, C, F, kAppendAlpha, 1>(k.full, alpha_lanes, alpha_bits, transparent);
    r[2] = g.pixels<T, C, F, kAppendAlpha, 2>(k.full, alpha_lanes, alpha_bits, transparent);
    r[3] = g.pixels<T, C, F, kAppendAlpha, 3>(k.full, alpha_lanes, alpha_bits, transparent);
    storeGroup<T, kAppendAlpha ? 4 : C>(o, r);
  }
  if (i < n) transparent += scalar(k, out + static_cast<std::ptrdiff_t>(i) * kOutPixel, n - i, sx + i, sy + i, valid + i, 1, nullptr);
  return transparent;
}

}  // namespace artcam::avx2

#endif
