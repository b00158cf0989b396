// AVX2 kernels of the 8-bit sampler (span_sampler.cpp only; issue 5, "SIMD where it pays").
//
// Runtime dispatch only: these functions carry __attribute__((target("avx2"))), the rest of the
// program keeps the x86-64 baseline, and span_sampler.cpp picks them when the CPU reports AVX2
// (the build never targets the host CPU as a whole). They compute EXACTLY what the scalar 8-bit interior path computes —
// the same float→fixed-point rounding (q = int(f · 1024 + 0.5), no FMA), the same integer
// bilinear with weights of 1/1024 and the same rounding — eight pixels at a time, so the tests
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

#include "core/render/span_sampler.h"

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

// Bilinear, C = 3 or 4 interleaved 8-bit channels (alpha, if any, premultiplied like the rest).
// Positions, weights and byte offsets for eight pixels at once; then each pixel's two taps of
// each row come in with one 8-byte load (gathers measured slower here than plain loads), are
// shuffled into (left, right) pairs per channel and weighted by one multiply-add:
// top = p00 (1024 − ax) + p01 ax, the scalar path's integers exactly.
template <int C, bool kAppendAlpha = false>
__attribute__((target("avx2"))) long long bilinearU8(const SpanSampler::Context& k, std::uint8_t* out,
                                                     int n, const float* sx, const float* sy,
                                                     const unsigned char* valid, ScalarSpanU8 scalar) {
  static_assert(C == 3 || C == 4);
  static_assert(!kAppendAlpha || C == 3);  // RGB in, RGBA out: alpha = coverage, 1 inside
  constexpr int kOut = kAppendAlpha ? 4 : C;
  const __m256 half = _mm256_set1_ps(0.5f), scale = _mm256_set1_ps(1024.0f);
  const __m256 xmax = _mm256_set1_ps(static_cast<float>(k.width) - 1.0f);
  // RGB: each 8-byte load reads two bytes past the right tap, so the lower row must not be
  // the image's last (the scalar routine takes those pixels).
  const __m256 ymax = _mm256_set1_ps(static_cast<float>(k.height) - (C == 3 ? 2.5f : 1.0f));
  const __m256i xlim = _mm256_set1_epi32(k.width - 2), ylim = _mm256_set1_epi32(k.height - 2);
  const __m256i row = _mm256_set1_epi32(static_cast<int>(k.src_row));
  const __m256i full_weight = _mm256_set1_epi32(1024);
  // Per 128-bit lane: bytes 0–7 the top row's 8-byte load, 8–15 the bottom row's; out: the
  // top row's (left, right) pairs per channel in bytes 0–7, the bottom row's in 8–15, so that
  // unpacklo/unpackhi with zero widen them to 16-bit pairs for the multiply-add.
  const __m128i pairs = C == 4 ? _mm_setr_epi8(0, 4, 1, 5, 2, 6, 3, 7, 8, 12, 9, 13, 10, 14, 11, 15)
                               : _mm_setr_epi8(0, 3, 1, 4, 2, 5, -1, -1, 8, 11, 9, 12, 10, 13, -1, -1);
  const __m256i pairs2 = _mm256_broadcastsi128_si256(pairs);
  const __m256i round2 = _mm256_set1_epi32(1 << 19);
  const std::ptrdiff_t row_bytes = k.src_row;
  long long transparent = 0;
  alignas(32) std::int32_t off[8], wx[8], wy[8];
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx + i), half);
    const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy + i), half);
    if (!allInterior(fx, fy, xmax, ymax, valid + i)) {
      transparent += scalar(k, out + i * kOut, 8, sx + i, sy + i, valid + i);
      continue;
    }
    const __m256i qx = _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(fx, scale), half));
    const __m256i qy = _mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(fy, scale), half));
    const __m256i x0 = _mm256_min_epi32(_mm256_srai_epi32(qx, 10), xlim);
    const __m256i y0 = _mm256_min_epi32(_mm256_srai_epi32(qy, 10), ylim);
    const __m256i ax = _mm256_sub_epi32(qx, _mm256_slli_epi32(x0, 10));
    const __m256i ay = _mm256_sub_epi32(qy, _mm256_slli_epi32(y0, 10));
    const __m256i xoff = C == 4 ? _mm256_slli_epi32(x0, 2) : _mm256_add_epi32(x0, _mm256_slli_epi32(x0, 1));
    _mm256_store_si256(static_cast<__m256i*>(static_cast<void*>(off)),
                       _mm256_add_epi32(_mm256_mullo_epi32(y0, row), xoff));
    // (1024 − ax) in the low 16 bits, ax in the high: the multiply-add's weight pair.
    _mm256_store_si256(static_cast<__m256i*>(static_cast<void*>(wx)),
                       _mm256_or_si256(_mm256_sub_epi32(full_weight, ax), _mm256_slli_epi32(ax, 16)));
    _mm256_store_si256(static_cast<__m256i*>(static_cast<void*>(wy)), ay);
    // Two pixels per 256-bit register, one per 128-bit lane: [p_j row 0 | p_j row 1] and
    // [p_j+1 row 0 | p_j+1 row 1] as 8-byte loads, shuffled into (left, right) pairs per
    // channel, widened, weighted, combined vertically, packed.
    const __m256i wx8 = _mm256_load_si256(static_cast<const __m256i*>(static_cast<const void*>(wx)));
    const __m256i wy8 = _mm256_load_si256(static_cast<const __m256i*>(static_cast<const void*>(wy)));
    std::uint8_t* o = out + i * kOut;
    for (int j = 0; j < 8; j += 2, o += 2 * kOut) {
      const std::uint8_t* p0 = k.src + off[j];
      const std::uint8_t* p1 = k.src + off[j + 1];
      std::uint64_t a0, b0, a1, b1;
      std::memcpy(&a0, p0, 8);
      std::memcpy(&b0, p0 + row_bytes, 8);
      std::memcpy(&a1, p1, 8);
      std::memcpy(&b1, p1 + row_bytes, 8);
      const __m256i taps = _mm256_shuffle_epi8(
          _mm256_set_epi64x(static_cast<long long>(b1), static_cast<long long>(a1),
                            static_cast<long long>(b0), static_cast<long long>(a0)),
          pairs2);
      const __m256i lane_pick = _mm256_setr_epi32(j, j, j, j, j + 1, j + 1, j + 1, j + 1);
      const __m256i weight_x = _mm256_permutevar8x32_epi32(wx8, lane_pick);
      const __m256i weight_y = _mm256_permutevar8x32_epi32(wy8, lane_pick);
      const __m256i zero = _mm256_setzero_si256();
      const __m256i top = _mm256_madd_epi16(_mm256_unpacklo_epi8(taps, zero), weight_x);
      const __m256i bottom = _mm256_madd_epi16(_mm256_unpackhi_epi8(taps, zero), weight_x);
      const __m256i sum = _mm256_add_epi32(
          _mm256_add_epi32(_mm256_slli_epi32(top, 10), _mm256_mullo_epi32(_mm256_sub_epi32(bottom, top), weight_y)),
          round2);
      const __m256i v = _mm256_srli_epi32(sum, 20);
      const __m256i bytes = _mm256_packus_epi16(_mm256_packus_epi32(v, v), zero);
      std::uint32_t w0 = static_cast<std::uint32_t>(_mm256_cvtsi256_si32(bytes));
      std::uint32_t w1 = static_cast<std::uint32_t>(_mm256_extract_epi32(bytes, 4));
      if constexpr (kAppendAlpha) {
        w0 |= 0xFF000000u;
        w1 |= 0xFF000000u;
      }
      // RGB: 4-byte stores whose spare byte the next pixel overwrites; the group's last pixel
      // stores exactly three (the byte after it may belong to another thread's row).
      std::memcpy(o, &w0, 4);
      std::memcpy(o + kOut, &w1, kOut == 4 || j + 1 < 7 ? 4 : 3);
      if (k.src_alpha >= 0)
        transparent += (((w0 >> (8 * k.src_alpha)) & 0xFFu) == 0) + (((w1 >> (8 * k.src_alpha)) & 0xFFu) == 0);
    }
  }
  if (i < n) transparent += scalar(k, out + i * kOut, n - i, sx + i, sy + i, valid + i);
  return transparent;
}

// Nearest, C = 3 or 4: offsets for eight pixels at once, then one 4-byte load and store each.
// RGB's 4-byte load reads one byte past the pixel, so the tap must not be on the last row.
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
  long long transparent = 0;
  alignas(32) std::int32_t off[8];
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
    _mm256_store_si256(static_cast<__m256i*>(static_cast<void*>(off)),
                       _mm256_add_epi32(_mm256_mullo_epi32(y, row), xoff));
    std::uint8_t* o = out + i * kOut;
    for (int j = 0; j < 8; ++j, o += kOut) {
      std::uint32_t word;
      std::memcpy(&word, k.src + off[j], 4);
      if constexpr (kAppendAlpha) word |= 0xFF000000u;
      std::memcpy(o, &word, kOut == 4 || j < 7 ? 4 : 3);
      if (k.src_alpha >= 0) transparent += ((word >> (8 * k.src_alpha)) & 0xFFu) == 0;
    }
  }
  if (i < n) transparent += scalar(k, out + i * kOut, n - i, sx + i, sy + i, valid + i);
  return transparent;
}

}  // namespace artcam::avx2

#endif
