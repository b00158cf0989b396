// SPDX-License-Identifier: Apache-2.0
// AVX2 kernels of the 8-bit sampler (span_sampler.cpp only; SIMD where it pays). The 16-bit
// and float ones are in span_sampler_avx2_wide.h, which shares the helpers here (allInterior,
// allOutside, toRegisters, prefetchRowsAhead).
//
// Runtime dispatch only: these functions carry __attribute__((target("avx2"))), the rest of the
// program keeps the x86-64 baseline, and span_sampler.cpp picks them when the CPU reports AVX2
// (the build never targets the host CPU as a whole). They compute EXACTLY what the scalar 8-bit
// interior path computes — the same float→fixed-point rounding (no FMA), the same integer
// bilinear (rows by 1/255, columns by 1/256) and the same rounding — eight pixels at a time, so the tests
// can demand bit-identical output from the scalar fallback. A group of eight with any pixel
// outside the interior (or without a preimage) goes to the scalar routine, which owns the
// border semantics.
//
// Memory: RGB pixels are 3 bytes and the loads are 4 or 8 bytes wide, so the interior test of
// the vector paths keeps the lower tap off the image's last row (the bytes read past a pixel
// are then the next row's); stores never write past the span.
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#define ARTCAM_HAVE_AVX2_SAMPLER 1

#include "core/sampling/span_sampler.h"

#include <immintrin.h>

#include <cstdint>
#include <cstring>

namespace artcam::avx2 {

using ScalarSpanU8 = long long (*)(const SpanSampler::Context&, std::uint8_t* out, int n,
                                   const float* sx, const float* sy, const unsigned char* valid);

// Eight lanes of the interior test of the scalar path: valid and 0 ≤ f < size − 1 − margin.
__attribute__((target("avx2"))) inline bool allInterior(__m256 fx, __m256 fy, __m256 xmax,
                                                        __m256 ymax, const unsigned char* valid) {
  std::uint64_t v;
  std::memcpy(&v, valid, 8);
  // Every valid byte is 0 or 1: all eight set means v == 0x0101…01.
  if (v != 0x0101010101010101ull) return false;
  const __m256 zero = _mm256_setzero_ps();
  const __m256 in = _mm256_and_ps(
      _mm256_and_ps(_mm256_cmp_ps(fx, zero, _CMP_GE_OQ), _mm256_cmp_ps(fy, zero, _CMP_GE_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(fx, xmax, _CMP_LT_OQ), _mm256_cmp_ps(fy, ymax, _CMP_LT_OQ)));
  return _mm256_movemask_ps(in) == 0xFF;
}

// Eight lanes without a single tap inside the source (or without a preimage): the scalar path
// (bilinearTap's first test, NaN included) writes zeros there, transparent — every layout
// (colour 0, alpha or coverage 0). A lens's corners outside the source are whole groups of
// these; they need no per-pixel pass.
__attribute__((target("avx2"))) inline bool allOutside(__m256 fx, __m256 fy, const SpanSampler::Context& k,
                                                       const unsigned char* valid) {
  const __m256 minus_one = _mm256_set1_ps(-1.0f);
  const __m256 w = _mm256_set1_ps(static_cast<float>(k.width)), h = _mm256_set1_ps(static_cast<float>(k.height));
  const __m256 some_tap = _mm256_and_ps(
      _mm256_and_ps(_mm256_cmp_ps(fx, minus_one, _CMP_GT_OQ), _mm256_cmp_ps(fy, minus_one, _CMP_GT_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(fx, w, _CMP_LT_OQ), _mm256_cmp_ps(fy, h, _CMP_LT_OQ)));
  const __m128i v8 = _mm_loadl_epi64(static_cast<const __m128i*>(static_cast<const void*>(valid)));
  const __m256i has = _mm256_cmpgt_epi32(_mm256_cvtepu8_epi32(v8), _mm256_setzero_si256());
  return _mm256_movemask_ps(_mm256_and_ps(some_tap, _mm256_castsi256_ps(has))) == 0;
}

// Eight 32-bit byte offsets moved from a vector to general registers, two per 64-bit
// extract: a round trip through memory stalls on store forwarding (in both samplers).
struct Offsets8 {
  std::uint64_t pair[4];
  [[gnu::always_inline]] std::int32_t operator[](int i) const {
    return static_cast<std::int32_t>(pair[i >> 1] >> (32 * (i & 1)));
  }
};

__attribute__((target("avx2"), always_inline)) inline Offsets8 toRegisters(__m256i off) {
  const __m128i lo = _mm256_castsi256_si128(off), hi = _mm256_extracti128_si256(off, 1);
  return {{static_cast<std::uint64_t>(_mm_cvtsi128_si64(lo)), static_cast<std::uint64_t>(_mm_extract_epi64(lo, 1)),
           static_cast<std::uint64_t>(_mm_cvtsi128_si64(hi)), static_cast<std::uint64_t>(_mm_extract_epi64(hi, 1))}};
}

// Source rows ahead of the one being read (without it the 8-bit samplers wait on memory for
// much of their time). The warp walks each span down its band (warp.cpp), so the rows this
// group of pixels reads now, plus kPrefetchRows, are what the same span reads about
// kPrefetchRows output rows later (a magnification near 1; elsewhere a harmless miss): far
// enough ahead to cover the memory latency, near enough to stay in L1. Only the lines of the
// group's first tap (the next groups' lines follow in order). A prefetch never faults, so the
// address may lie past the image; it is formed as an integer so no pointer leaves it.
constexpr int kPrefetchRows = 4;

__attribute__((target("avx2"), always_inline)) inline void prefetchRowsAhead(const SpanSampler::Context& k,
                                                                            const std::uint8_t* tap, int bytes = 32) {
  const std::uintptr_t ahead = reinterpret_cast<std::uintptr_t>(tap) +
                               static_cast<std::uintptr_t>(kPrefetchRows * k.src_row);
  _mm_prefetch(reinterpret_cast<const char*>(ahead), _MM_HINT_T0);
  _mm_prefetch(reinterpret_cast<const char*>(ahead + static_cast<std::uintptr_t>(bytes - 1)), _MM_HINT_T0);
}

// bilinearTap's integers for eight lanes (fx, fy = position − ½), the 16-bit and float
// kernels' taps: ⌊f⌋ as cvtt(f + 1) − 1 for f ≥ −1; a NaN or huge position converts to
// INT_MIN, − 1 wraps to INT_MAX, outside any range the callers test.
struct Floor8 {
  __m256i x0, y0;
};
__attribute__((target("avx2"), always_inline)) inline Floor8 tapFloor(__m256 fx, __m256 fy) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256i int_one = _mm256_set1_epi32(1);
  return {_mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_add_ps(fx, one)), int_one),
          _mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_add_ps(fy, one)), int_one)};
}

// The scalar bilinear's fixed point for eight lanes (fx, fy = position − ½, interior): the
// left tap x0, the row y0, column weight ax in 0 … 256 and row weight ay in 0 … 255, rounded
// as span_sampler.cpp's BilinearQuanta rounds them (no FMA).
struct Quanta8 {
  __m256i x0, y0, ax, ay;
};
__attribute__((target("avx2"), always_inline)) inline Quanta8 quantise(__m256 fx, __m256 fy, __m256i xlim) {
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256i qx = _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(fx, _mm256_set1_ps(256.0f)), half));
  const __m256i x0 = _mm256_min_epi32(_mm256_srai_epi32(qx, 8), xlim);
  const __m256i y0 = _mm256_cvttps_epi32(fy);
  const __m256 row_fraction = _mm256_sub_ps(fy, _mm256_cvtepi32_ps(y0));
  return {x0, y0, _mm256_sub_epi32(qx, _mm256_slli_epi32(x0, 8)),
          _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(row_fraction, _mm256_set1_ps(255.0f)), half))};
}

// bilinearU8's pieces. Pixels p and p + 4: [top 8 bytes | bottom 8 bytes] in one lane each.
__attribute__((target("avx2"), always_inline)) inline __m256i pixelPair(const std::uint8_t* src,
                                                                        const std::uint8_t* below,
                                                                        const Offsets8& top, int p) {
  const auto rows = [&](int q) __attribute__((always_inline)) {
    const __m128i t = _mm_loadl_epi64(static_cast<const __m128i*>(static_cast<const void*>(src + top[q])));
    return _mm_castpd_si128(
        _mm_loadh_pd(_mm_castsi128_pd(t), static_cast<const double*>(static_cast<const void*>(below + top[q]))));
  };
  const __m128i a = rows(p), b = rows(p + 4);
  return _mm256_inserti128_si256(_mm256_castsi128_si256(a), b, 1);
}

// Rows, then columns: (255 − ay) top + ay bottom − 128 · 255 per tap and channel (exact in 16
// bits), then (256 − ax) left + ax right + the bias, >> 8: one pixel per lane, channels in 32
// bits, still to be divided by 255.
__attribute__((target("avx2"), always_inline)) inline __m256i weighPair(__m256i taps, __m256i y_weights,
                                                                        __m256i x_weights, __m256i pairs,
                                                                        __m256i sign, __m256i bias) {
  const __m256i signed_taps = _mm256_xor_si256(_mm256_shuffle_epi8(taps, pairs), sign);
  const __m256i columns = _mm256_maddubs_epi16(y_weights, signed_taps);
  return _mm256_srli_epi32(_mm256_add_epi32(_mm256_madd_epi16(columns, x_weights), bias), 8);
}

// Bilinear, C = 3 or 4 interleaved 8-bit channels (alpha, if any, premultiplied like the rest),
// the scalar path's integers (span_sampler.cpp) eight pixels at a time:
// - positions → fixed point, byte offsets and weights for all eight lanes at once;
// - per pixel, one 8-byte load from each row (taps x0 and x0 + 1 and two spare bytes) into one
//   128-bit lane, [top | bottom]; pixels k and k + 4 share a 256-bit register, so each one's
//   weights are an in-lane broadcast of its 32-bit lane (no lane crossing);
// - one shuffle orders the bytes as (top, bottom) pairs per channel and tap, one
//   _mm256_maddubs_epi16 weighs the rows: the unsigned operand is the weights (255 − ay, ay),
//   the signed one the pixels − 128 (xor 0x80), so L − 128 · 255 is exact in 16 bits;
// - one _mm256_madd_epi16 weighs the columns (256 − ax, ax) into 32 bits; + the bias, >> 8,
//   packed to 16 bits, ÷ 255 as (q · 0x8081) >> 23 (exact for every 16-bit q);
// - two packs put pixels 0–3 in the low lane and 4–7 in the high one, in order.
template <int C, bool kAppendAlpha = false>
__attribute__((target("avx2"))) long long bilinearU8(const SpanSampler::Context& k, std::uint8_t* out,
                                                     int n, const float* sx, const float* sy,
                                                     const unsigned char* valid, ScalarSpanU8 scalar) {
  static_assert(C == 3 || C == 4);
  static_assert(!kAppendAlpha || C == 3);  // RGB in, RGBA out: alpha = coverage, 1 inside
  constexpr int kOut = kAppendAlpha ? 4 : C;
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256 xmax = _mm256_set1_ps(static_cast<float>(k.width) - 1.0f);
  // The 8-byte loads read past the right tap (RGB: two bytes), so the lower row must not be
  // the image's last.
  const __m256 ymax = _mm256_set1_ps(static_cast<float>(k.height) - 2.5f);
  const __m256i xlim = _mm256_set1_epi32(k.width - 2);
  const __m256i row = _mm256_set1_epi32(static_cast<int>(k.src_row));
  const __m256i c255 = _mm256_set1_epi32(255), c256 = _mm256_set1_epi32(256);
  const __m256i zero = _mm256_setzero_si256();
  const __m256i sign = _mm256_set1_epi8(static_cast<char>(0x80));
  const __m256i bias = _mm256_set1_epi32(128 * 255 * 256 + 32640);
  const __m256i div255 = _mm256_set1_epi16(static_cast<short>(0x8081));
  // [top 8 bytes | bottom 8 bytes] → (top, bottom) pairs for (c of tap 0, c of tap 1), c = R, G, B(, A).
  const __m128i pairs = C == 4 ? _mm_setr_epi8(0, 8, 4, 12, 1, 9, 5, 13, 2, 10, 6, 14, 3, 11, 7, 15)
                               : _mm_setr_epi8(0, 8, 3, 11, 1, 9, 4, 12, 2, 10, 5, 13, -1, -1, -1, -1);
  const __m256i pairs2 = _mm256_broadcastsi128_si256(pairs);
  // RGBx → RGB per lane: four pixels' 16 bytes into 12.
  const __m256i squeeze = _mm256_broadcastsi128_si256(
      _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1));
  const std::uint8_t* below = k.src + k.src_row;
  long long transparent = 0;
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx + i), half);
    const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy + i), half);
    if (!allInterior(fx, fy, xmax, ymax, valid + i)) {
      if (allOutside(fx, fy, k, valid + i)) {
        std::memset(out + i * kOut, 0, 8 * kOut);
        transparent += 8;
      } else {
        transparent += scalar(k, out + i * kOut, 8, sx + i, sy + i, valid + i);
      }
      continue;
    }
    const auto [x0, y0, ax, ay] = quantise(fx, fy, xlim);
    const __m256i xoff = C == 4 ? _mm256_slli_epi32(x0, 2) : _mm256_add_epi32(x0, _mm256_slli_epi32(x0, 1));
    const __m256i off = _mm256_add_epi32(_mm256_mullo_epi32(y0, row), xoff);
    const Offsets8 top = toRegisters(off);
    prefetchRowsAhead(k, k.src + top[0]);
    // Bytes (255 − ay, ay, 255 − ay, ay) per lane; words (256 − ax, ax).
    const __m256i wy_pair = _mm256_or_si256(_mm256_sub_epi32(c255, ay), _mm256_slli_epi32(ay, 8));
    const __m256i wy = _mm256_or_si256(wy_pair, _mm256_slli_epi32(wy_pair, 16));
    const __m256i wx = _mm256_or_si256(_mm256_sub_epi32(c256, ax), _mm256_slli_epi32(ax, 16));
    const __m256i p0 = weighPair(pixelPair(k.src, below, top, 0), _mm256_shuffle_epi32(wy, 0x00),
                                 _mm256_shuffle_epi32(wx, 0x00), pairs2, sign, bias);
    const __m256i p1 = weighPair(pixelPair(k.src, below, top, 1), _mm256_shuffle_epi32(wy, 0x55),
                                 _mm256_shuffle_epi32(wx, 0x55), pairs2, sign, bias);
    const __m256i p2 = weighPair(pixelPair(k.src, below, top, 2), _mm256_shuffle_epi32(wy, 0xAA),
                                 _mm256_shuffle_epi32(wx, 0xAA), pairs2, sign, bias);
    const __m256i p3 = weighPair(pixelPair(k.src, below, top, 3), _mm256_shuffle_epi32(wy, 0xFF),
                                 _mm256_shuffle_epi32(wx, 0xFF), pairs2, sign, bias);
    // Low lane: pixels 0 1 2 3, high lane: 4 5 6 7, four bytes each.
    // ⌊q / 255⌋ = (q · 0x8081) >> 23 for every 16-bit q.
    const __m256i q01 = _mm256_srli_epi16(_mm256_mulhi_epu16(_mm256_packus_epi32(p0, p1), div255), 7);
    const __m256i q23 = _mm256_srli_epi16(_mm256_mulhi_epu16(_mm256_packus_epi32(p2, p3), div255), 7);
    __m256i bytes = _mm256_packus_epi16(q01, q23);
    std::uint8_t* o = out + i * kOut;
    if constexpr (C == 4 || kAppendAlpha) {
      if constexpr (kAppendAlpha) bytes = _mm256_or_si256(bytes, _mm256_set1_epi32(static_cast<int>(0xFF000000u)));
      _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(o)), bytes);
      if (k.src_alpha >= 0) {
        const unsigned zero_bytes = static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(bytes, zero)));
        transparent += __builtin_popcount(zero_bytes & (0x11111111u << k.src_alpha));
      }
    } else {
      // 24 bytes: the low lane's 12 with a 16-byte store whose spare four the high lane's
      // first store overwrites; nothing past the group is written.
      const __m256i packed = _mm256_shuffle_epi8(bytes, squeeze);
      const __m128i high = _mm256_extracti128_si256(packed, 1);
      _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o)), _mm256_castsi256_si128(packed));
      _mm_storel_epi64(static_cast<__m128i*>(static_cast<void*>(o + 12)), high);
      const std::uint32_t last = static_cast<std::uint32_t>(_mm_extract_epi32(high, 2));
      std::memcpy(o + 20, &last, 4);
      if (k.src_alpha >= 0)
        for (int p = 0; p < 8; ++p) transparent += o[3 * p + k.src_alpha] == 0;
    }
  }
  if (i < n) transparent += scalar(k, out + i * kOut, n - i, sx + i, sy + i, valid + i);
  return transparent;
}

// Nearest, C = 3 or 4: offsets for eight pixels at once, into general registers
// (toRegisters), one 4-byte load each,
// assembled four pixels per 128-bit register and stored as in bilinearU8. RGB's 4-byte load
// reads one byte past the pixel, so the tap must not be on the last row.
template <int C, bool kAppendAlpha = false>
__attribute__((target("avx2"))) long long nearestU8(const SpanSampler::Context& k, std::uint8_t* out,
                                                    int n, const float* sx, const float* sy,
                                                    const unsigned char* valid, ScalarSpanU8 scalar) {
  static_assert(C == 3 || C == 4);
  static_assert(!kAppendAlpha || C == 3);  // RGB in, RGBA out: alpha = coverage, 1 inside
  constexpr int kOut = kAppendAlpha ? 4 : C;
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256 xmax = _mm256_set1_ps(static_cast<float>(k.width) - 1.0f);
  const __m256 ymax = _mm256_set1_ps(static_cast<float>(k.height) - (C == 3 ? 1.5f : 1.0f));
  const __m256i row = _mm256_set1_epi32(static_cast<int>(k.src_row));
  const __m128i squeeze = _mm_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
  const __m128i opaque = _mm_set1_epi32(static_cast<int>(0xFF000000u));
  long long transparent = 0;
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx + i), half);
    const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy + i), half);
    if (!allInterior(fx, fy, xmax, ymax, valid + i)) {
      transparent += scalar(k, out + i * kOut, 8, sx + i, sy + i, valid + i);
      continue;
    }
    const __m256i x = _mm256_cvttps_epi32(_mm256_add_ps(fx, half));
    const __m256i y = _mm256_cvttps_epi32(_mm256_add_ps(fy, half));
    const __m256i xoff = C == 4 ? _mm256_slli_epi32(x, 2) : _mm256_add_epi32(x, _mm256_slli_epi32(x, 1));
    const __m256i off = _mm256_add_epi32(_mm256_mullo_epi32(y, row), xoff);
    const Offsets8 at = toRegisters(off);
    prefetchRowsAhead(k, k.src + at[0]);
    const auto four = [&](int p) __attribute__((always_inline)) {
      const auto load = [&](int q) __attribute__((always_inline)) { return _mm_loadu_si32(k.src + at[q]); };
      return _mm_unpacklo_epi64(_mm_unpacklo_epi32(load(p), load(p + 1)), _mm_unpacklo_epi32(load(p + 2), load(p + 3)));
    };
    __m128i first = four(0), second = four(4);
    std::uint8_t* o = out + i * kOut;
    if constexpr (C == 4 || kAppendAlpha) {
      if constexpr (kAppendAlpha) {
        first = _mm_or_si128(first, opaque);
        second = _mm_or_si128(second, opaque);
      }
      _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o)), first);
      _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o + 16)), second);
      if (k.src_alpha >= 0) {
        const __m128i z = _mm_setzero_si128();
        const unsigned zero_bytes = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(first, z))) |
                                    static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(second, z))) << 16;
        transparent += __builtin_popcount(zero_bytes & (0x11111111u << k.src_alpha));
      }
    } else {
      const __m128i a = _mm_shuffle_epi8(first, squeeze), b = _mm_shuffle_epi8(second, squeeze);
      _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o)), a);
      _mm_storel_epi64(static_cast<__m128i*>(static_cast<void*>(o + 12)), b);
      const std::uint32_t last = static_cast<std::uint32_t>(_mm_extract_epi32(b, 2));
      std::memcpy(o + 20, &last, 4);
      if (k.src_alpha >= 0)
        for (int p = 0; p < 8; ++p) transparent += o[3 * p + k.src_alpha] == 0;
    }
  }
  if (i < n) transparent += scalar(k, out + i * kOut, n - i, sx + i, sy + i, valid + i);
  return transparent;
}

// 16 bytes at lo in the low lane, 16 at hi in the high one.
__attribute__((target("avx2"), always_inline)) inline __m256i halves(const std::uint8_t* lo, const std::uint8_t* hi) {
  return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(lo)))),
                                 _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(hi))), 1);
}

// 255 × channel c of the eight consecutive RGB8 pixels from p (the channel's byte of the
// first): two loads within the 24 bytes, two shuffles.
__attribute__((target("avx2"), always_inline)) inline __m256i consecutiveTimes255(const std::uint8_t* p, int c,
                                                                                  __m128i pick_first,
                                                                                  __m128i pick_second) {
  const __m128i a = _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(p - c)));
  const __m128i b = _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(p - c + 8)));
  const __m256i v = _mm256_cvtepu8_epi32(_mm_or_si128(_mm_shuffle_epi8(a, pick_first), _mm_shuffle_epi8(b, pick_second)));
  return _mm256_sub_epi32(_mm256_slli_epi32(v, 8), v);
}

// Three colour channels, each at positions of its own (chromatic aberration), RGB8 → RGBA8
// with alpha 255: the scalar interior bilinear's integers (BilinearQuanta in span_sampler.cpp)
// per channel, eight pixels at a time. direct[c], where not null, is channel c of the source
// pixel under output pixel 0, the channel's positions being whole pixels on one interior row
// (the caller checked): its values are read from there, with no position or test. Per channel and lane the four taps are gathered as bytes
// (top left, bottom left, top right, bottom right), then weighed as bilinearU8 weighs them: one
// _mm256_maddubs_epi16 for the rows (pixels − 128, so exact in 16 bits), one _mm256_madd_epi16
// for the columns; the three channels are divided by 255 together in 16 bits and interleaved
// by one shuffle. (Not each channel in 32 bits with three vpmulld: that is slower.)
// The taps: where a channel's eight pixels lie nearly consecutive in the source (the usual
// case: chromatic aberration scales by a hair), one 16-byte load per half and row and byte
// shuffles; elsewhere one 4-byte load per pixel and row at the left tap's byte, whose bytes 0
// and 3 are the channel at taps x0 and x0 + 1 (nothing read past the taps). Groups of eight
// while every channel's pixels are interior (allInterior), or while some channel has no tap
// inside for any of them (allOutside: its alpha is 0, so the merge's is, and the group is
// zeros, counted in `transparent`); returns the pixels written: n, or the start of the first
// group that is neither. n is a multiple of 8.
__attribute__((target("avx2"))) inline int bilinearChannelsRgb8(const SpanSampler::Context& k, std::uint8_t* out,
                                                                 int n, const float* const* sx,
                                                                 const float* const* sy,
                                                                 const unsigned char* const* valid,
                                                                 const std::uint8_t* const* direct,
                                                                 long long& transparent) {
  const __m256 xmax = _mm256_set1_ps(static_cast<float>(k.width) - 1.0f);
  const __m256 ymax = _mm256_set1_ps(static_cast<float>(k.height) - 1.0f);
  const __m256 half = _mm256_set1_ps(0.5f);
  const __m256i xlim = _mm256_set1_epi32(k.width - 2);
  const __m256i row = _mm256_set1_epi32(static_cast<int>(k.src_row));
  const __m256i c255 = _mm256_set1_epi32(255), c256 = _mm256_set1_epi32(256);
  const __m256i sign = _mm256_set1_epi8(static_cast<char>(0x80));
  const __m256i bias = _mm256_set1_epi32(128 * 255 * 256 + 32640);
  const __m256i div255 = _mm256_set1_epi16(static_cast<short>(0x8081));
  const __m256i opaque = _mm256_set1_epi32(static_cast<int>(0xFF000000u));
  const __m256i step3 = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  // Channel c of pixels 0–3 from the 16 bytes at pixel 0, of pixels 4–7 from those at byte 8.
  const __m128i pick_first[3] = {_mm_setr_epi8(0, 3, 6, 9, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                                 _mm_setr_epi8(1, 4, 7, 10, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
                                 _mm_setr_epi8(2, 5, 8, 11, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1)};
  const __m128i pick_second[3] = {_mm_setr_epi8(-1, -1, -1, -1, 4, 7, 10, 13, -1, -1, -1, -1, -1, -1, -1, -1),
                                  _mm_setr_epi8(-1, -1, -1, -1, 5, 8, 11, 14, -1, -1, -1, -1, -1, -1, -1, -1),
                                  _mm_setr_epi8(-1, -1, -1, -1, 6, 9, 12, 15, -1, -1, -1, -1, -1, -1, -1, -1)};
  const __m256i minus_one = _mm256_set1_epi32(-1), thirteen = _mm256_set1_epi32(13), three = _mm256_set1_epi32(3);
  // Shuffle controls with a lane's other bytes zeroed: (d, ·, d + 3, ·) for the top row's taps.
  const __m256i zero_odd = _mm256_set1_epi32(static_cast<int>(0x80008000u));
  const __m256i zero_first = _mm256_set1_epi32(0x80);
  // The 4-byte words at the left taps: byte 0 is tap x0, byte 3 tap x0 + 1; the top row's to
  // bytes 0 and 2 of the lane, the bottom row's to 1 and 3.
  const __m256i word_top = _mm256_broadcastsi128_si256(
      _mm_setr_epi8(0, -1, 3, -1, 4, -1, 7, -1, 8, -1, 11, -1, 12, -1, 15, -1));
  const __m256i word_below = _mm256_broadcastsi128_si256(
      _mm_setr_epi8(-1, 0, -1, 3, -1, 4, -1, 7, -1, 8, -1, 11, -1, 12, -1, 15));
  // [R0–3 G0–3 B0–3 ·] per lane → R G B · per pixel.
  const __m256i to_pixels = _mm256_broadcastsi128_si256(
      _mm_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15));
  // One past the image's last byte, as an offset from its first.
  const std::ptrdiff_t end = (k.height - 1) * k.src_row + 3 * static_cast<std::ptrdiff_t>(k.width);
  const int* top = static_cast<const int*>(static_cast<const void*>(k.src));
  const int* below = static_cast<const int*>(static_cast<const void*>(k.src + k.src_row));
  for (int i = 0; i + 8 <= n; i += 8) {
    // Channel c's eight values before the division by 255 (so q / 255 is the result), in 32 bits.
    __m256i q[3];
    bool outside = false;
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      if (direct[c]) {
        q[c] = consecutiveTimes255(direct[c] + 3 * i, c, pick_first[c], pick_second[c]);
        continue;
      }
      const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx[c] + i), half);
      const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy[c] + i), half);
      if (!allInterior(fx, fy, xmax, ymax, valid[c] + i)) {
        if (!allOutside(fx, fy, k, valid[c] + i)) return i;
        outside = true;
        break;
      }
      const auto [x0, y0, ax, ay] = quantise(fx, fy, xlim);
      const __m256i off = _mm256_add_epi32(_mm256_mullo_epi32(y0, row),
                                           _mm256_add_epi32(_mm256_add_epi32(x0, _mm256_slli_epi32(x0, 1)),
                                                            _mm256_set1_epi32(c)));
      // Exactly eight consecutive pixel centres of one row (a channel the camera leaves in
      // place, as lateral chromatic aberration leaves green): the weights are (1, 0), the
      // value is the tap, read from two loads.
      const std::int32_t first = _mm256_cvtsi256_si32(off);
      const __m256i centres = _mm256_and_si256(
          _mm256_cmpeq_epi32(_mm256_or_si256(ax, ay), _mm256_setzero_si256()),
          _mm256_cmpeq_epi32(off, _mm256_add_epi32(_mm256_set1_epi32(first), step3)));
      if (_mm256_movemask_epi8(centres) == -1) {
        q[c] = consecutiveTimes255(k.src + first, c, pick_first[c], pick_second[c]);
        continue;
      }
      __m256i taps;  // bytes (top left, bottom left, top right, bottom right) per lane
      // Each half's four left taps within 12 bytes of its first (a magnification near 1: the
      // channel's pixels nearly consecutive): one 16-byte load per half and row, and the taps
      // picked by byte shuffles (a lane's tap byte at d, the right tap at d + 3).
      const __m256i d = _mm256_sub_epi32(off, _mm256_shuffle_epi32(off, 0));
      const std::int32_t second = _mm256_extract_epi32(off, 4);
      const bool window = _mm256_movemask_epi8(_mm256_and_si256(_mm256_cmpgt_epi32(d, minus_one),
                                                                _mm256_cmpgt_epi32(thirteen, d))) == -1 &&
                          std::max(first, second) + k.src_row + 16 <= end;
      if (window) {
        if (c == 0) prefetchRowsAhead(k, k.src + first);
        const __m256i t = halves(k.src + first, k.src + second);
        const __m256i b = halves(k.src + first + k.src_row, k.src + second + k.src_row);
        const __m256i pick_top = _mm256_or_si256(_mm256_or_si256(d, _mm256_slli_epi32(_mm256_add_epi32(d, three), 16)),
                                                 zero_odd);
        const __m256i pick_below = _mm256_or_si256(_mm256_slli_epi32(pick_top, 8), zero_first);
        taps = _mm256_or_si256(_mm256_shuffle_epi8(t, pick_top), _mm256_shuffle_epi8(b, pick_below));
      } else {
        const Offsets8 at = toRegisters(off);
        if (c == 0) prefetchRowsAhead(k, k.src + at[0]);
        // Eight 4-byte loads per row, not a gather: vpgatherdd is slower here.
        const auto word = [](const int* base, std::int32_t byte) __attribute__((always_inline)) {
          int v;
          std::memcpy(&v, static_cast<const std::uint8_t*>(static_cast<const void*>(base)) + byte, 4);
          return v;
        };
        const __m256i t = _mm256_setr_epi32(word(top, at[0]), word(top, at[1]), word(top, at[2]), word(top, at[3]),
                                            word(top, at[4]), word(top, at[5]), word(top, at[6]), word(top, at[7]));
        const __m256i b = _mm256_setr_epi32(word(below, at[0]), word(below, at[1]), word(below, at[2]), word(below, at[3]),
                                            word(below, at[4]), word(below, at[5]), word(below, at[6]), word(below, at[7]));
        taps = _mm256_or_si256(_mm256_shuffle_epi8(t, word_top), _mm256_shuffle_epi8(b, word_below));
      }
      // Bytes (255 − ay, ay, 255 − ay, ay) per lane; words (256 − ax, ax).
      const __m256i wy_pair = _mm256_or_si256(_mm256_sub_epi32(c255, ay), _mm256_slli_epi32(ay, 8));
      const __m256i wy = _mm256_or_si256(wy_pair, _mm256_slli_epi32(wy_pair, 16));
      const __m256i wx = _mm256_or_si256(_mm256_sub_epi32(c256, ax), _mm256_slli_epi32(ax, 16));
      const __m256i columns = _mm256_maddubs_epi16(wy, _mm256_xor_si256(taps, sign));
      q[c] = _mm256_srli_epi32(_mm256_add_epi32(_mm256_madd_epi16(columns, wx), bias), 8);
    }
    if (outside) {
      _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(out + 4 * i)), _mm256_setzero_si256());
      transparent += 8;
      continue;
    }
    // ⌊q / 255⌋ = (q · 0x8081) >> 23 for every 16-bit q; per lane [R0–3 G0–3 | B0–3 0].
    const __m256i rg = _mm256_srli_epi16(_mm256_mulhi_epu16(_mm256_packus_epi32(q[0], q[1]), div255), 7);
    const __m256i b0 = _mm256_srli_epi16(_mm256_mulhi_epu16(_mm256_packus_epi32(q[2], _mm256_setzero_si256()), div255), 7);
    const __m256i rgba = _mm256_or_si256(_mm256_shuffle_epi8(_mm256_packus_epi16(rg, b0), to_pixels), opaque);
    _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(out + 4 * i)), rgba);
  }
  return n;
}

}  // namespace artcam::avx2

#endif
