// SPDX-License-Identifier: Apache-2.0
// AVX-512 (BW + VBMI) bilinear for 8-bit RGB (span_sampler.cpp only; SIMD where it
// pays). Runtime dispatch only, as span_sampler_avx2.h: these functions carry a target
// attribute, span_sampler.cpp picks them when the CPU reports avx512bw, avx512vl and
// avx512vbmi, and they compute EXACTLY the scalar 8-bit interior integers (the same
// float → fixed-point rounding without FMA, rows by 1/255, columns by 1/256, one rounding), so
// the tests demand bit-identical output.
//
// Why it is faster than the AVX2 clone: that one spends two loads and an insert per pixel to
// bring its taps in. Where a map is smooth — nearly everywhere in a photo warp — sixteen
// neighbouring output pixels read one or two source rows within a few dozen bytes, so here a
// group of sixteen loads ONE 64-byte window of the upper row and one of the lower row, and
// three vpermt2b pick every pixel's taps out of the 128 bytes already as (upper, lower)
// byte pairs for _mm512_maddubs_epi16 — no per-pixel load. A group that crosses a source row
// (upper rows y and y + 1) also loads row y + 2 and blends a second permute for the pixels one
// row down. A group spanning more rows or more than 20 source columns (minified by more than
// about 1.25×), or touching a border, runs the AVX2 clone (which owns the same integers).
//
// Memory: the 64-byte windows start at the group's leftmost tap and may run past the row's
// last pixel into the next row; the interior test keeps the lower row off the image's last
// row, so with rows of at least 64 bytes (checked at dispatch) no read leaves the image.
#pragma once

#include "core/render/span_sampler_avx2.h"

#include <algorithm>

#ifdef ARTCAM_HAVE_AVX2_SAMPLER
#define ARTCAM_HAVE_AVX512_SAMPLER 1

// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*() (a self-initialised variable),
// which -Wmaybe-uninitialized reports wherever they are inlined: a false positive.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"


namespace artcam::avx512 {

#define ARTCAM_AVX512_TARGET target("avx2,avx512f,avx512bw,avx512vl,avx512vbmi")

// Per tap vector j (dwords 16 j … 16 j + 15): each byte's pixel (for the window offsets),
// each word's pixel (row weights, as the word index 2 p of a dword lane) and each dword's
// pixel (column weights); and each byte's offset within its pixel's taps: channel c + 3 t
// (tap t) + 64 for the lower row (vpermt2b's second table).
struct RgbLayout {
  alignas(64) std::uint8_t byte_pixel[3][64];
  alignas(64) std::uint8_t byte_offset[3][64];
  alignas(64) std::uint16_t word_pixel[3][32];
  alignas(64) std::uint32_t dword_pixel[3][16];
};

constexpr RgbLayout makeRgbLayout() {
  RgbLayout l{};
  for (int j = 0; j < 3; ++j)
    for (int b = 0; b < 64; ++b) {
      const int d = 16 * j + b / 4, p = d / 3, c = d % 3, t = (b % 4) / 2, lower = b % 2;
      l.byte_pixel[j][b] = static_cast<std::uint8_t>(p);
      l.byte_offset[j][b] = static_cast<std::uint8_t>(c + 3 * t + 64 * lower);
      if (b % 2 == 0) l.word_pixel[j][b / 2] = static_cast<std::uint16_t>(2 * p);
      if (b % 4 == 0) l.dword_pixel[j][b / 4] = static_cast<std::uint32_t>(p);
    }
  return l;
}

inline constexpr RgbLayout kRgbLayout = makeRgbLayout();

// A product the compiler must round on its own: AVX-512F has 512-bit FMA, and GCC would
// otherwise fuse x · s + 0.5 into one rounding the scalar path does not make.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512 roundedProduct(__m512 x, __m512 s) {
  __m512 p = _mm512_mul_ps(x, s);
  asm("" : "+v"(p));
  return p;
}

// Bilinear RGB8 → RGB8 (no alpha), sixteen pixels per group from two 64-byte windows.
// Byte layout of the three 512-bit tap vectors: dword d = 3 p + c (pixel p, channel c) holds
// (upper x0, lower x0, upper x0 + 1, lower x0 + 1) of that channel, so one maddubs weighs the
// rows ((255 − ay, ay) per byte pair, pixels − 128 as in the AVX2 clone) and one madd the
// columns ((256 − ax, ax) per word pair); dwords come out in output order, so truncating
// down-converts (the values fit) restore the interleaved bytes without a shuffle.
__attribute__((ARTCAM_AVX512_TARGET)) inline long long bilinearRgb8(const SpanSampler::Context& k,
                                                                    std::uint8_t* out, int n,
                                                                    const float* sx, const float* sy,
                                                                    const unsigned char* valid,
                                                                    avx2::ScalarSpanU8 scalar) {
  const __m512 half = _mm512_set1_ps(0.5f), scale_x = _mm512_set1_ps(256.0f), scale_y = _mm512_set1_ps(255.0f);
  const __m512 zero_ps = _mm512_setzero_ps();
  const __m512 xmax = _mm512_set1_ps(static_cast<float>(k.width) - 1.0f);
  const __m512 ymax = _mm512_set1_ps(static_cast<float>(k.height) - 2.5f);  // lower row not the last
  const __m512i xlim = _mm512_set1_epi32(k.width - 2);
  const __m512i c255 = _mm512_set1_epi32(255), c256 = _mm512_set1_epi32(256);
  const __m512i max_rel = _mm512_set1_epi32(19);  // taps x0 … x0 + 1 of 16 pixels in 64 bytes
  const __m512i sign = _mm512_set1_epi8(static_cast<char>(0x80));
  const __m512i bias = _mm512_set1_epi32(128 * 255 * 256 + 32640);
  const __m512i div255 = _mm512_set1_epi16(static_cast<short>(0x8081));
  const __m128i ones = _mm_set1_epi8(1);
  __m512i expand_b[3], offset_b[3], expand_w[3], expand_d[3];
  for (int j = 0; j < 3; ++j) {
    expand_b[j] = _mm512_load_si512(kRgbLayout.byte_pixel[j]);
    offset_b[j] = _mm512_load_si512(kRgbLayout.byte_offset[j]);
    expand_w[j] = _mm512_load_si512(kRgbLayout.word_pixel[j]);
    expand_d[j] = _mm512_load_si512(kRgbLayout.dword_pixel[j]);
  }
  long long transparent = 0;
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    std::uint8_t* o = out + i * 3;
    const __m512 fx = _mm512_sub_ps(_mm512_loadu_ps(sx + i), half);
    const __m512 fy = _mm512_sub_ps(_mm512_loadu_ps(sy + i), half);
    const __mmask16 inside = _mm512_cmp_ps_mask(fx, zero_ps, _CMP_GE_OQ) & _mm512_cmp_ps_mask(fy, zero_ps, _CMP_GE_OQ) &
                             _mm512_cmp_ps_mask(fx, xmax, _CMP_LT_OQ) & _mm512_cmp_ps_mask(fy, ymax, _CMP_LT_OQ);
    const __m128i v = _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(valid + i)));
    if (inside != 0xFFFF || _mm_cmpeq_epi8_mask(v, ones) != 0xFFFF) {
      transparent += avx2::bilinearU8<3>(k, o, 16, sx + i, sy + i, valid + i, scalar);
      continue;
    }
    const __m512i qx = _mm512_cvttps_epi32(_mm512_add_ps(roundedProduct(fx, scale_x), half));
    const __m512i x0 = _mm512_min_epi32(_mm512_srai_epi32(qx, 8), xlim);
    const __m512i y0 = _mm512_cvttps_epi32(fy);
    const int x_first = _mm_cvtsi128_si32(_mm512_castsi512_si128(x0));
    // The upper row: the lower of the first and last pixels' rows, not a full reduction (a
    // smooth map's rows are monotone over sixteen pixels; where one in between is lower, its
    // negative dy fails the 0 … 1 test below and the group goes to the AVX2 clone).
    const int y_first = std::min(_mm_cvtsi128_si32(_mm512_castsi512_si128(y0)),
                                 _mm_extract_epi32(_mm512_extracti32x4_epi32(y0, 3), 3));
    const __m512i rel = _mm512_sub_epi32(x0, _mm512_set1_epi32(x_first));
    const __m512i dy = _mm512_sub_epi32(y0, _mm512_set1_epi32(y_first));  // 0 or 1 below
    const __mmask16 lower_pair = _mm512_test_epi32_mask(dy, dy);
    if (_mm512_cmple_epu32_mask(dy, _mm512_set1_epi32(1)) != 0xFFFF ||
        _mm512_cmple_epu32_mask(rel, max_rel) != 0xFFFF) {
      transparent += avx2::bilinearU8<3>(k, o, 16, sx + i, sy + i, valid + i, scalar);
      continue;
    }
    const __m512i ax = _mm512_sub_epi32(qx, _mm512_slli_epi32(x0, 8));  // 0 … 256
    const __m512i ay = _mm512_cvttps_epi32(
        _mm512_add_ps(roundedProduct(_mm512_sub_ps(fy, _mm512_cvtepi32_ps(y0)), scale_y), half));  // 0 … 255
    const std::uint8_t* upper = k.src + static_cast<std::ptrdiff_t>(y_first) * k.src_row + 3 * x_first;
    const __m512i top = _mm512_loadu_si512(upper);
    const __m512i bottom = _mm512_loadu_si512(upper + k.src_row);
    avx2::prefetchRowsAhead(k, upper, 64);  // as the AVX2 clone: rows further down
    // Pixels one row lower (the group crosses a source row): their taps from rows + 1, + 2.
    __m512i third = bottom, dy_bytes = _mm512_setzero_si512();
    if (lower_pair) {
      third = _mm512_loadu_si512(upper + 2 * k.src_row);
      dy_bytes = _mm512_castsi128_si512(_mm512_cvtepi32_epi8(dy));
    }
    // 3 × rel as bytes, the window offset of each pixel's first tap (≤ 57).
    const __m512i rel3 = _mm512_castsi128_si512(_mm512_cvtepi32_epi8(_mm512_add_epi32(rel, _mm512_slli_epi32(rel, 1))));
    // Words (255 − ay) | ay << 8 and dwords (256 − ax) | ax << 16, one per pixel.
    const __m512i wy = _mm512_or_si512(_mm512_sub_epi32(c255, ay), _mm512_slli_epi32(ay, 8));
    const __m512i wx = _mm512_or_si512(_mm512_sub_epi32(c256, ax), _mm512_slli_epi32(ax, 16));
    __m256i words[3];
#pragma GCC unroll 3
    for (int j = 0; j < 3; ++j) {
      const __m512i index = _mm512_add_epi8(_mm512_permutexvar_epi8(expand_b[j], rel3), offset_b[j]);
      __m512i taps = _mm512_permutex2var_epi8(top, index, bottom);
      if (lower_pair) {
        const __m512i down = _mm512_permutexvar_epi8(expand_b[j], dy_bytes);
        taps = _mm512_mask_blend_epi8(_mm512_test_epi8_mask(down, down), taps,
                                      _mm512_permutex2var_epi8(bottom, index, third));
      }
      taps = _mm512_xor_si512(taps, sign);
      const __m512i rows = _mm512_maddubs_epi16(_mm512_permutexvar_epi16(expand_w[j], wy), taps);
      const __m512i cols = _mm512_madd_epi16(rows, _mm512_permutexvar_epi32(expand_d[j], wx));
      // (X + 32640) >> 8 ≤ 65152 for X = (256 − ax) L + ax R: exact in 16 bits.
      words[j] = _mm512_cvtepi32_epi16(_mm512_srli_epi32(_mm512_add_epi32(cols, bias), 8));
    }
    // ⌊q / 255⌋ = (q · 0x8081) >> 23 for every 16-bit q, then bytes in output order.
    const __m512i q01 = _mm512_inserti64x4(_mm512_castsi256_si512(words[0]), words[1], 1);
    const __m512i d01 = _mm512_srli_epi16(_mm512_mulhi_epu16(q01, div255), 7);
    const __m256i d2 = _mm256_srli_epi16(_mm256_mulhi_epu16(words[2], _mm512_castsi512_si256(div255)), 7);
    _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(o)), _mm512_cvtepi16_epi8(d01));
    _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o + 32)), _mm256_cvtepi16_epi8(d2));
  }
  if (i < n) transparent += avx2::bilinearU8<3>(k, out + i * 3, n - i, sx + i, sy + i, valid + i, scalar);
  return transparent;
}

#undef ARTCAM_AVX512_TARGET

}  // namespace artcam::avx512

#pragma GCC diagnostic pop

#endif
