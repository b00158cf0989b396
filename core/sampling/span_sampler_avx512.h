// SPDX-License-Identifier: Apache-2.0
// AVX-512 (BW + VBMI) bilinear for 8-bit RGB (to RGB or RGBA; and each colour channel at its
// own positions, bilinearChannelsRgb8), and for 16-bit and float RGB (bilinearWideRgb, below)
// (span_sampler.cpp only; SIMD where it pays). Runtime dispatch only, as span_sampler_avx2.h:
// these functions carry a target attribute, span_sampler.cpp picks them when the CPU reports
// avx512bw, avx512vl and avx512vbmi, and they compute EXACTLY the scalar path's numbers (8-bit:
// the same float → fixed-point rounding without FMA, rows by 1/255, columns by 1/256, one
// rounding; float: the same operations in the same order), so the tests demand bit-identical
// output.
//
// Why it is faster than the AVX2 clone: that one spends two loads and an insert per pixel to
// bring its taps in. Where a map is smooth — nearly everywhere in a photo warp — sixteen
// neighbouring output pixels read one or two source rows within a few dozen bytes, so here a
// group of sixteen loads ONE 64-byte window of the upper row and one of the lower row, and
// three vpermt2b pick every pixel's taps out of the 128 bytes already as (upper, lower)
// byte pairs for _mm512_maddubs_epi16 — no per-pixel load. A group that crosses a source row
// (upper rows y and y + 1) also loads row y + 2 and blends a second permute for the pixels one
// row down. A group spanning more rows or more than 20 source columns (minified by more than
// about 1.25×) loads each pixel's taps on its own as the AVX2 clone does, sixteen at a time
// (gatherWeigh); a group touching a border or an invalid pixel runs the AVX2 clone (which owns
// the same integers and the border semantics).
//
// Memory: the 64-byte windows start at the group's leftmost tap and may run past the row's
// last pixel into the next row; the interior test keeps the lower row off the image's last
// row, so with rows of at least 64 bytes (checked at dispatch) no read leaves the image.
#pragma once

#include "core/sampling/span_sampler_avx2.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#ifdef ARTCAM_HAVE_AVX2_SAMPLER
#define ARTCAM_HAVE_AVX512_SAMPLER 1

// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*() (a self-initialised variable),
// which -Wmaybe-uninitialized (and, for _mm512_castsi128_si512, -Wuninitialized) reports
// wherever they are inlined: a false positive.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"


namespace artcam::avx512 {

#define ARTCAM_AVX512_TARGET target("avx2,avx512f,avx512bw,avx512vl,avx512vbmi")

// A product the compiler must round on its own: AVX-512F has 512-bit FMA, and GCC would
// otherwise fuse x · s + 0.5 into one rounding the scalar path does not make.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512 roundedProduct(__m512 x, __m512 s) {
  __m512 p = _mm512_mul_ps(x, s);
  asm("" : "+v"(p));
  return p;
}

// The sixteen pixels of a group the windows cannot take (minified by more than ~1.25×, or
// crossing more than one source row: most of a strong barrel's frame) by the AVX2 clone's
// per-pixel loads, at 512 bits: one 8-byte load per row and pixel, [upper | lower] in one
// 128-bit lane, pixel 4 L + P in lane L of register P, so each pixel's weights are an in-lane
// broadcast of its dword. The clone's integers (weighPair), so the same bytes. Gathered in
// place, with groups without a valid pixel zeroed inline, not by calling the clone per group:
// where most groups gather (a strong barrel), per-group calls would cost more than the clone
// on whole spans.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m128i rowPairAt(const std::uint8_t* upper,
                                                                             const std::uint8_t* lower, int at) {
  const __m128i t = _mm_loadl_epi64(static_cast<const __m128i*>(static_cast<const void*>(upper + at)));
  return _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(t), static_cast<const double*>(static_cast<const void*>(lower + at))));
}

template <int P>
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512i gatherWeigh(const std::uint8_t* upper,
                                                                               const std::uint8_t* lower,
                                                                               const int* at, __m512i wy, __m512i wx,
                                                                               __m512i pairs, __m512i sign,
                                                                               __m512i bias) {
  __m512i taps = _mm512_castsi128_si512(rowPairAt(upper, lower, at[P]));
  taps = _mm512_inserti32x4(taps, rowPairAt(upper, lower, at[P + 4]), 1);
  taps = _mm512_inserti32x4(taps, rowPairAt(upper, lower, at[P + 8]), 2);
  taps = _mm512_inserti32x4(taps, rowPairAt(upper, lower, at[P + 12]), 3);
  const __m512i signed_taps = _mm512_xor_si512(_mm512_shuffle_epi8(taps, pairs), sign);
  const __m512i columns = _mm512_maddubs_epi16(_mm512_shuffle_epi32(wy, static_cast<_MM_PERM_ENUM>(P * 0x55)), signed_taps);
  return _mm512_srli_epi32(
      _mm512_add_epi32(_mm512_madd_epi16(columns, _mm512_shuffle_epi32(wx, static_cast<_MM_PERM_ENUM>(P * 0x55))), bias), 8);
}

// What the 8-bit window kernels (bilinearRgb8, bilinearChannelsRgb8) share.
//
// Sixteen pixels are interior (the window kernels' own test: the lower row is not the image's
// last, so a 64-byte load from a tap stays inside) and valid (`valid`: their sixteen flags).
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline bool interior16(__m512 fx, __m512 fy, __m128i valid,
                                                                           const SpanSampler::Context& k) {
  const __m512 zero = _mm512_setzero_ps();
  const __m512 xmax = _mm512_set1_ps(static_cast<float>(k.width) - 1.0f);
  const __m512 ymax = _mm512_set1_ps(static_cast<float>(k.height) - 2.5f);  // lower row not the last
  const __mmask16 inside = _mm512_cmp_ps_mask(fx, zero, _CMP_GE_OQ) & _mm512_cmp_ps_mask(fy, zero, _CMP_GE_OQ) &
                           _mm512_cmp_ps_mask(fx, xmax, _CMP_LT_OQ) & _mm512_cmp_ps_mask(fy, ymax, _CMP_LT_OQ);
  return inside == 0xFFFF && _mm_cmpeq_epi8_mask(valid, _mm_set1_epi8(1)) == 0xFFFF;
}

// The scalar bilinear's fixed point for sixteen interior positions (fx, fy = position − ½),
// as the AVX2 clone's quantise: the left tap x0 and row y0, bytes (255 − ay, ay, 255 − ay, ay)
// and words (256 − ax, ax) per dword; and where the group lies for the windows.
struct Quanta16 {
  __m512i x0, y0, wy, wx;
  __m512i rel;  // x0 − the first pixel's x0
  __mmask16 lower_pair;  // pixels one row below y_first
  int x_first, y_first;
  bool fits;  // rows y_first or one below, taps within one 64-byte window per row
};
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline Quanta16 quantise16(__m512 fx, __m512 fy,
                                                                               const SpanSampler::Context& k) {
  const __m512 half = _mm512_set1_ps(0.5f);
  const __m512i c255 = _mm512_set1_epi32(255), c256 = _mm512_set1_epi32(256);
  Quanta16 g;
  const __m512i qx = _mm512_cvttps_epi32(_mm512_add_ps(roundedProduct(fx, _mm512_set1_ps(256.0f)), half));
  g.x0 = _mm512_min_epi32(_mm512_srai_epi32(qx, 8), _mm512_set1_epi32(k.width - 2));
  g.y0 = _mm512_cvttps_epi32(fy);
  g.x_first = _mm_cvtsi128_si32(_mm512_castsi512_si128(g.x0));
  // The upper row: the lower of the first and last pixels' rows, not a full reduction (a
  // smooth map's rows are monotone over sixteen pixels; where one in between is lower, its
  // negative dy fails the 0 … 1 test below and the group does not fit).
  g.y_first = std::min(_mm_cvtsi128_si32(_mm512_castsi512_si128(g.y0)),
                       _mm_extract_epi32(_mm512_extracti32x4_epi32(g.y0, 3), 3));
  g.rel = _mm512_sub_epi32(g.x0, _mm512_set1_epi32(g.x_first));
  const __m512i dy = _mm512_sub_epi32(g.y0, _mm512_set1_epi32(g.y_first));  // 0 or 1 where it fits
  g.lower_pair = _mm512_test_epi32_mask(dy, dy);
  // Taps x0 … x0 + 1 of sixteen pixels in 64 bytes: rel ≤ 19.
  g.fits = _mm512_cmple_epu32_mask(dy, _mm512_set1_epi32(1)) == 0xFFFF &&
           _mm512_cmple_epu32_mask(g.rel, _mm512_set1_epi32(19)) == 0xFFFF;
  const __m512i ax = _mm512_sub_epi32(qx, _mm512_slli_epi32(g.x0, 8));  // 0 … 256
  const __m512i ay = _mm512_cvttps_epi32(
      _mm512_add_ps(roundedProduct(_mm512_sub_ps(fy, _mm512_cvtepi32_ps(g.y0)), _mm512_set1_ps(255.0f)), half));  // 0 … 255
  const __m512i wy_pair = _mm512_or_si512(_mm512_sub_epi32(c255, ay), _mm512_slli_epi32(ay, 8));
  g.wy = _mm512_or_si512(wy_pair, _mm512_slli_epi32(wy_pair, 16));
  g.wx = _mm512_or_si512(_mm512_sub_epi32(c256, ax), _mm512_slli_epi32(ax, 16));
  return g;
}

// The windows of a group that fits: 64 bytes of its upper row from its first tap, of the row
// below, and (for pixels one row lower) of the row below that.
struct Windows16 {
  __m512i top, bottom, third;
  __m512i base;  // 3 × rel (≤ 57), each pixel's first tap in the windows, in every byte of its dword
};
// `prefetch`: also the lines a few rows down (as the AVX2 clone), once per group of pixels.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline Windows16 windows16(const Quanta16& g,
                                                                               const SpanSampler::Context& k,
                                                                               bool prefetch = true) {
  // Each dword's low byte into all four of its bytes (vpshufb, within 128-bit lanes).
  const __m512i byte0 = _mm512_set_epi8(60, 60, 60, 60, 56, 56, 56, 56, 52, 52, 52, 52, 48, 48, 48, 48,
                                        44, 44, 44, 44, 40, 40, 40, 40, 36, 36, 36, 36, 32, 32, 32, 32,
                                        28, 28, 28, 28, 24, 24, 24, 24, 20, 20, 20, 20, 16, 16, 16, 16,
                                        12, 12, 12, 12, 8, 8, 8, 8, 4, 4, 4, 4, 0, 0, 0, 0);
  const std::uint8_t* upper = k.src + static_cast<std::ptrdiff_t>(g.y_first) * k.src_row + 3 * g.x_first;
  Windows16 w;
  w.top = _mm512_loadu_si512(upper);
  w.bottom = _mm512_loadu_si512(upper + k.src_row);
  w.third = g.lower_pair ? _mm512_loadu_si512(upper + 2 * k.src_row) : w.bottom;
  if (prefetch) avx2::prefetchRowsAhead(k, upper, 64);
  w.base = _mm512_shuffle_epi8(_mm512_add_epi32(g.rel, _mm512_slli_epi32(g.rel, 1)), byte0);
  return w;
}

// Channel c of the sixteen pixels, before the division by 255: its taps picked from the windows
// by one vpermt2b as (upper x0, lower x0, upper x0 + 1, lower x0 + 1) — bytes c, 64 + c, c + 3,
// 64 + c + 3 of the two tables — one maddubs for the rows (pixels − 128, so exact in 16 bits),
// one madd for the columns.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512i windowChannel(const Windows16& w, const Quanta16& g,
                                                                                 int c) {
  const __m512i index = _mm512_add_epi8(w.base, _mm512_set1_epi32(0x43034000 + 0x01010101 * c));
  __m512i taps = _mm512_permutex2var_epi8(w.top, index, w.bottom);
  if (g.lower_pair)
    taps = _mm512_mask_blend_epi32(g.lower_pair, taps, _mm512_permutex2var_epi8(w.bottom, index, w.third));
  const __m512i rows = _mm512_maddubs_epi16(g.wy, _mm512_xor_si512(taps, _mm512_set1_epi8(static_cast<char>(0x80))));
  // (X + 32640) >> 8 ≤ 65152 for X = (256 − ax) L + ax R: exact in 16 bits.
  return _mm512_srli_epi32(_mm512_add_epi32(_mm512_madd_epi16(rows, g.wx), _mm512_set1_epi32(128 * 255 * 256 + 32640)), 8);
}

// Three channels' values divided by 255 ((q · 0x8081) >> 23, exact for every 16-bit q) and
// packed to bytes within 128-bit lanes: lane L (pixels 4 L … 4 L + 3) holds R R R R G G G G
// B B B B B B B B, for kInterleaveRgb or kInterleaveRgba to order.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512i packChannels(__m512i r, __m512i g, __m512i b) {
  const __m512i div255 = _mm512_set1_epi16(static_cast<short>(0x8081));
  const __m512i rg255 = _mm512_srli_epi16(_mm512_mulhi_epu16(_mm512_packus_epi32(r, g), div255), 7);
  const __m512i bb255 = _mm512_srli_epi16(_mm512_mulhi_epu16(_mm512_packus_epi32(b, b), div255), 7);
  return _mm512_packus_epi16(rg255, bb255);
}
// Output byte 3 p + c (RGB) or 4 p + c (RGBA, alpha's byte then set) from packChannels' byte
// 16 (p / 4) + 4 c + p % 4.
alignas(64) inline constexpr std::uint8_t kInterleaveRgb[64] = {
    0,  4,  8,  1,  5,  9,  2,  6,  10, 3,  7,  11, 16, 20, 24, 17, 21, 25, 18, 22, 26, 19,
    23, 27, 32, 36, 40, 33, 37, 41, 34, 38, 42, 35, 39, 43, 48, 52, 56, 49, 53, 57, 50, 54,
    58, 51, 55, 59, 0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0};
alignas(64) inline constexpr std::uint8_t kInterleaveRgba[64] = {
    0,  4,  8,  0, 1,  5,  9,  0, 2,  6,  10, 0, 3,  7,  11, 0, 16, 20, 24, 0, 17, 21,
    25, 0,  18, 22, 26, 0, 19, 23, 27, 0, 32, 36, 40, 0, 33, 37, 41, 0, 34, 38, 42, 0,
    35, 39, 43, 0,  48, 52, 56, 0, 49, 53, 57, 0, 50, 54, 58, 0, 51, 55, 59, 0};

// Sixteen pixels' bytes in output order (RGB: the first 48; RGBA: all 64, alpha's then set).
template <bool kAppendAlpha>
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline void storeSixteen(std::uint8_t* o, __m512i bytes) {
  if constexpr (kAppendAlpha) {
    _mm512_storeu_si512(o, _mm512_or_si512(bytes, _mm512_set1_epi32(static_cast<int>(0xFF000000u))));
  } else {
    _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(o)), _mm512_castsi512_si256(bytes));
    _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o + 32)), _mm512_extracti32x4_epi32(bytes, 2));
  }
}

// Bilinear RGB8 → RGB8 (no alpha), or → RGBA8 with alpha full inside (kAppendAlpha: the
// render front door's and the studio's layout), sixteen pixels per group from two 64-byte
// windows. One channel at a time (planar): dword p of channel c's tap vector holds (upper x0, lower
// x0, upper x0 + 1, lower x0 + 1) of pixel p, so every pixel's weights sit in its own dword
// lane as the positions do and need no permute: one maddubs weighs the rows ((255 − ay, ay)
// per byte pair, pixels − 128 as in the AVX2 clone), one madd the columns ((256 − ax, ax) per
// word pair). The three channels are packed to words, divided by 255 together and packed to
// bytes, and one vpermb interleaves them into RGB. (Not the taps in output order, dword 3 p + c,
// which takes three permutes per channel spreading weights and indices: ~20 shuffles per group
// against 9 here.)
template <bool kAppendAlpha = false>
__attribute__((ARTCAM_AVX512_TARGET)) inline long long bilinearRgb8(const SpanSampler::Context& k,
                                                                    std::uint8_t* out, int n,
                                                                    const float* sx, const float* sy,
                                                                    const unsigned char* valid,
                                                                    avx2::ScalarSpanU8 scalar) {
  const __m512 half = _mm512_set1_ps(0.5f);
  const __m512i sign = _mm512_set1_epi8(static_cast<char>(0x80));
  const __m512i bias = _mm512_set1_epi32(128 * 255 * 256 + 32640);
  const __m512i div255 = _mm512_set1_epi16(static_cast<short>(0x8081));
  const __m512i interleave = _mm512_load_si512(kAppendAlpha ? kInterleaveRgba : kInterleaveRgb);
  constexpr int kOut = kAppendAlpha ? 4 : 3;
  // The gathered groups (gatherWeigh): (upper, lower) byte pairs per channel and tap, as the
  // AVX2 clone's; lane L of the packed result holds pixels 4 L … 4 L + 3 as RGBx.
  const __m512i pairs = _mm512_broadcast_i32x4(_mm_setr_epi8(0, 8, 3, 11, 1, 9, 4, 12, 2, 10, 5, 13, -1, -1, -1, -1));
  alignas(64) static constexpr std::uint8_t kSqueeze[64] = {
      0,  1,  2,  4,  5,  6,  8,  9,  10, 12, 13, 14, 16, 17, 18, 20, 21, 22, 24, 25, 26, 28,
      29, 30, 32, 33, 34, 36, 37, 38, 40, 41, 42, 44, 45, 46, 48, 49, 50, 52, 53, 54, 56, 57,
      58, 60, 61, 62, 0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0};
  const __m512i squeeze = _mm512_load_si512(kSqueeze);
  const __m512i row_bytes = _mm512_set1_epi32(static_cast<int>(k.src_row));
  const std::uint8_t* const lower_row = k.src + k.src_row;
  long long transparent = 0;
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    std::uint8_t* o = out + i * kOut;
    const __m512 fx = _mm512_sub_ps(_mm512_loadu_ps(sx + i), half);
    const __m512 fy = _mm512_sub_ps(_mm512_loadu_ps(sy + i), half);
    const __m128i v = _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(valid + i)));
    if (_mm_test_all_zeros(v, v)) {
      // No pixel has a preimage (a strong barrel's corners: half its groups): zeros, as the
      // AVX2 clone writes them, without its call.
      std::memset(o, 0, 16 * kOut);
      transparent += 16;
      continue;
    }
    if (!interior16(fx, fy, v, k)) {
      transparent += avx2::bilinearU8<3, kAppendAlpha>(k, o, 16, sx + i, sy + i, valid + i, scalar);
      continue;
    }
    const Quanta16 g = quantise16(fx, fy, k);
    if (!g.fits) {
      alignas(64) int at[16];  // each pixel's upper-left tap, bytes from k.src (32 bits: dispatch)
      _mm512_store_si512(at, _mm512_add_epi32(_mm512_mullo_epi32(g.y0, row_bytes),
                                              _mm512_add_epi32(g.x0, _mm512_slli_epi32(g.x0, 1))));
      // As the AVX2 clone, which prefetches for each group of eight.
      avx2::prefetchRowsAhead(k, k.src + at[0]);
      avx2::prefetchRowsAhead(k, k.src + at[8]);
      const __m512i p0 = gatherWeigh<0>(k.src, lower_row, at, g.wy, g.wx, pairs, sign, bias);
      const __m512i p1 = gatherWeigh<1>(k.src, lower_row, at, g.wy, g.wx, pairs, sign, bias);
      const __m512i p2 = gatherWeigh<2>(k.src, lower_row, at, g.wy, g.wx, pairs, sign, bias);
      const __m512i p3 = gatherWeigh<3>(k.src, lower_row, at, g.wy, g.wx, pairs, sign, bias);
      const __m512i q01 = _mm512_srli_epi16(_mm512_mulhi_epu16(_mm512_packus_epi32(p0, p1), div255), 7);
      const __m512i q23 = _mm512_srli_epi16(_mm512_mulhi_epu16(_mm512_packus_epi32(p2, p3), div255), 7);
      const __m512i rgbx = _mm512_packus_epi16(q01, q23);
      storeSixteen<kAppendAlpha>(o, kAppendAlpha ? rgbx : _mm512_permutexvar_epi8(squeeze, rgbx));
      continue;
    }
    const Windows16 w = windows16(g, k);
    storeSixteen<kAppendAlpha>(o, _mm512_permutexvar_epi8(interleave, packChannels(windowChannel(w, g, 0),
                                                                                   windowChannel(w, g, 1),
                                                                                   windowChannel(w, g, 2))));
  }
  if (i < n) transparent += avx2::bilinearU8<3, kAppendAlpha>(k, out + i * kOut, n - i, sx + i, sy + i, valid + i, scalar);
  return transparent;
}

// Lanes 0–7 of v in both halves of a 512-bit register.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512 bothHalves(__m256 v) {
  const __m256d d = _mm256_castps_pd(v);
  return _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castpd256_pd512(d), d, 1));
}

// 32 samples from p as floats, masked at the image's last sample (`end`, bytes from k.src; at
// least six samples remain from any tap's pixel): nothing past it is read. Float: two 512-bit
// loads; 16-bit: one, widened (each sample exactly as the scalar code converts it).
template <class T>
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline void sampleWindow(const SpanSampler::Context& k,
                                                                             std::int64_t end, const unsigned char* p,
                                                                             __m512& a, __m512& b) {
  const std::int64_t left = (end - (p - k.src)) / static_cast<std::int64_t>(sizeof(T));
  if constexpr (std::is_same_v<T, float>) {
    if (left >= 32) {  // nearly always: plain loads (masked ones measured several times slower)
      a = _mm512_loadu_ps(p);
      b = _mm512_loadu_ps(p + 64);
      return;
    }
    const __mmask16 m0 = left >= 16 ? 0xFFFF : static_cast<__mmask16>((1u << left) - 1u);
    const __mmask16 m1 = left <= 16 ? 0 : static_cast<__mmask16>((1u << (left - 16)) - 1u);
    a = _mm512_maskz_loadu_ps(m0, p);
    b = _mm512_maskz_loadu_ps(m1, p + 64);
  } else {
    static_assert(std::is_same_v<T, std::uint16_t>);
    const __m512i w = left >= 32 ? _mm512_loadu_si512(p)
                                 : _mm512_maskz_loadu_epi16(static_cast<__mmask32>((1u << left) - 1u), p);
    a = _mm512_cvtepi32_ps(_mm512_cvtepu16_epi32(_mm512_castsi512_si256(w)));
    b = _mm512_cvtepi32_ps(_mm512_cvtepu16_epi32(_mm512_extracti64x4_epi64(w, 1)));
  }
}

// avx2::bilinearChannelsRgb8 on the `count` pixels from pixel i (a multiple of 8).
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline int channelsClone(
    const SpanSampler::Context& k, std::uint8_t* out, int i, int count, const float* const* sx, const float* const* sy,
    const unsigned char* const* valid, const std::uint8_t* const* direct, long long& transparent) {
  const float* xs[3] = {sx[0] + i, sx[1] + i, sx[2] + i};
  const float* ys[3] = {sy[0] + i, sy[1] + i, sy[2] + i};
  const unsigned char* vs[3] = {valid[0] + i, valid[1] + i, valid[2] + i};
  const std::uint8_t* ds[3];
  for (int c = 0; c < 3; ++c) ds[c] = direct[c] ? direct[c] + 3 * i : nullptr;
  return avx2::bilinearChannelsRgb8(k, out + 4 * i, count, xs, ys, vs, ds, transparent);
}

// 255 × channel c of the sixteen consecutive RGB8 pixels from p (the channel's byte of the
// first), one dword each: what windowChannel gives at whole-pixel positions, divided by 255
// to the same byte (packChannels), as the AVX2 clone's consecutiveTimes255. The 48 bytes read
// are the sixteen pixels' own (the caller's direct rows hold them).
alignas(64) inline constexpr std::uint8_t kPickChannel[3][64] = {
    {0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 33, 36, 39, 42, 45},
    {1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 34, 37, 40, 43, 46},
    {2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 32, 35, 38, 41, 44, 47}};
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512i consecutiveTimes255(const std::uint8_t* p, int c) {
  const std::uint8_t* first = p - c;
  const __m512i bytes =
      _mm512_inserti32x4(_mm512_castsi256_si512(_mm256_loadu_si256(static_cast<const __m256i*>(static_cast<const void*>(first)))),
                         _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(first + 32))), 2);
  const __m512i v = _mm512_cvtepu8_epi32(
      _mm512_castsi512_si128(_mm512_permutexvar_epi8(_mm512_load_si512(kPickChannel[c]), bytes)));
  return _mm512_sub_epi32(_mm512_slli_epi32(v, 8), v);
}

// Three colour channels, each at positions of its own (chromatic aberration), RGB8 → RGBA8
// with alpha 255, sixteen pixels a group: each channel as bilinearRgb8's windows weigh one
// channel (the taps of the channel's own sixteen positions picked by one vpermt2b from a
// 64-byte window of its upper row and one of its lower row), so the AVX2 clone's integers and
// the same bytes; a whole-pixel channel (`direct`, the caller checked its row) read straight
// from its row, as the clone does. A channel whose group the windows cannot take (minified,
// crossing more than one row, on the lower border, not valid) sends the group to the AVX2
// clone (avx2::bilinearChannelsRgb8), which owns every other case: chromatic aberration
// scales by a hair, so nearly every group is a window group. Returns the pixels written, as
// the clone does; n is a multiple of 8.
__attribute__((ARTCAM_AVX512_TARGET)) inline int bilinearChannelsRgb8(const SpanSampler::Context& k, std::uint8_t* out,
                                                                     int n, const float* const* sx,
                                                                     const float* const* sy,
                                                                     const unsigned char* const* valid,
                                                                     const std::uint8_t* const* direct,
                                                                     long long& transparent) {
  const __m512 half = _mm512_set1_ps(0.5f);
  const __m512i interleave = _mm512_load_si512(kInterleaveRgba);
  int i = 0;
  for (; i + 16 <= n; i += 16) {
    __m512i q[3];
    bool windows = true, prefetch = true;
#pragma GCC unroll 3
    for (int c = 0; c < 3 && windows; ++c) {
      if (direct[c]) {
        q[c] = consecutiveTimes255(direct[c] + 3 * i, c);
        continue;
      }
      const __m512 fx = _mm512_sub_ps(_mm512_loadu_ps(sx[c] + i), half);
      const __m512 fy = _mm512_sub_ps(_mm512_loadu_ps(sy[c] + i), half);
      windows = interior16(fx, fy, _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(valid[c] + i))), k);
      if (!windows) break;
      const Quanta16 g = quantise16(fx, fy, k);
      windows = g.fits;
      if (windows) q[c] = windowChannel(windows16(g, k, prefetch), g, c);
      prefetch = false;  // once per group
    }
    if (!windows) {
      const int done = channelsClone(k, out, i, 16, sx, sy, valid, direct, transparent);
      if (done < 16) return i + done;
      continue;
    }
    storeSixteen<true>(out + 4 * i, _mm512_permutexvar_epi8(interleave, packChannels(q[0], q[1], q[2])));
  }
  return i < n ? i + channelsClone(k, out, i, n - i, sx, sy, valid, direct, transparent) : n;
}

// The AVX2 clone's bilinear in its order: rows of (left, right), then the two rows, + 0.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512 bilinearBlend(__m512 bx0, __m512 bx1, __m512 by0,
                                                                                __m512 by1, __m512 tl, __m512 tr,
                                                                                __m512 bl, __m512 br) {
  const __m512 top = _mm512_add_ps(roundedProduct(bx0, tl), roundedProduct(bx1, tr));
  const __m512 bottom = _mm512_add_ps(roundedProduct(bx0, bl), roundedProduct(bx1, br));
  return _mm512_add_ps(_mm512_setzero_ps(), _mm512_add_ps(roundedProduct(by0, top), roundedProduct(by1, bottom)));
}

// 64 samples of 16-bit RGB from p (two 512-bit loads), masked at the image's last sample
// (`end`, bytes from k.src): nothing past it is read.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline void wordWindow(const SpanSampler::Context& k,
                                                                           std::int64_t end, const unsigned char* p,
                                                                           __m512i window[2]) {
  const std::int64_t left = (end - (p - k.src)) / 2;
  for (int r = 0; r < 2; ++r) {
    const std::int64_t count = left - 32 * r;
    window[r] = count >= 32 ? _mm512_loadu_si512(p + 64 * r)
                            : _mm512_maskz_loadu_epi16(count <= 0 ? 0 : static_cast<__mmask32>((1u << count) - 1u), p + 64 * r);
  }
}

__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline __m512 wordsToFloats(__m256i w) {
  return _mm512_cvtepi32_ps(_mm512_cvtepu16_epi32(w));
}

// What the sixteen-pixel groups (wordGroup16, floatSixteen) share: the taps x0, y0 of sixteen
// positions as avx2::tapFloor gives them (fx, fy = position − ½; a NaN or huge position gives
// INT_MIN or INT_MAX, a negative tap a huge unsigned one) and the bilinear weights
// (1 − wx, wx, 1 − wy, wy) in the AVX2 clone's operations.
struct Taps16 {
  __m512i x0, y0;
  __m512 bx0, wx1, by0, wy1;
};
// False where a pixel is not valid or the image is under 2 × 2 (fits16's unsigned limits
// would then wrap).
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline bool taps16(const SpanSampler::Context& k, const float* sx,
                                                                       const float* sy, const unsigned char* valid,
                                                                       Taps16& t) {
  const __m128i v = _mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(valid)));
  if (_mm_cmpeq_epi8_mask(v, _mm_set1_epi8(1)) != 0xFFFF || k.width < 2 || k.height < 2) return false;
  const __m512 half = _mm512_set1_ps(0.5f), one = _mm512_set1_ps(1.0f);
  const __m512 fx = _mm512_sub_ps(_mm512_loadu_ps(sx), half), fy = _mm512_sub_ps(_mm512_loadu_ps(sy), half);
  const __m512i int_one = _mm512_set1_epi32(1);
  t.x0 = _mm512_sub_epi32(_mm512_cvttps_epi32(_mm512_add_ps(fx, one)), int_one);
  t.y0 = _mm512_sub_epi32(_mm512_cvttps_epi32(_mm512_add_ps(fy, one)), int_one);
  t.wx1 = _mm512_sub_ps(fx, _mm512_cvtepi32_ps(t.x0));
  t.wy1 = _mm512_sub_ps(fy, _mm512_cvtepi32_ps(t.y0));
  t.bx0 = _mm512_sub_ps(one, t.wx1);
  t.by0 = _mm512_sub_ps(one, t.wy1);
  return true;
}
// Every pixel interior (0 ≤ x0 ≤ w − 2, 0 ≤ y0 ≤ h − 2), on its upper row or one below
// (dy 0 or 1) and at most max_rel columns right of its group's first tap (rel), each test
// unsigned so that one compare also refuses negatives.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline bool fits16(const SpanSampler::Context& k, const Taps16& t,
                                                                       __m512i rel, __m512i dy, int max_rel) {
  __mmask16 fits = _mm512_cmple_epu32_mask(t.x0, _mm512_set1_epi32(k.width - 2));
  fits = _mm512_mask_cmple_epu32_mask(fits, t.y0, _mm512_set1_epi32(k.height - 2));
  fits = _mm512_mask_cmple_epu32_mask(fits, dy, _mm512_set1_epi32(1));
  fits = _mm512_mask_cmple_epu32_mask(fits, rel, _mm512_set1_epi32(max_rel));
  return fits == 0xFFFF;
}

// Sixteen pixels of bilinear 16-bit RGB, one channel at a time as bilinearRgb8 does: lane p of
// every register is pixel p, so the blend's arithmetic fills all sixteen lanes (the eight-pixel
// group below leaves half its blue lanes idle and sets up every eight pixels). A row's taps lie
// within 64 samples of the group's first tap (rel ≤ 19: 3 rel + 5 < 64), two 64-byte loads;
// one vpermt2w a row and channel picks the left taps (words 0–15) and the right ones (16–31),
// widened to floats; the arithmetic per pixel is the AVX2 clone's in its order
// (bilinearBlend), so the same bits. Returns false, writing nothing, for a group that is not
// interior, valid, within two source rows and 20 columns (or for an image under 2 × 2): the
// caller runs the eight-pixel path. Float is not taken this way: its 64-sample window is four
// registers, each tap two vpermt2ps and a blend, which costs more than two eights.
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline bool wordGroup16(const SpanSampler::Context& k,
                                                                            std::int64_t end, unsigned char* o,
                                                                            const float* sx, const float* sy,
                                                                            const unsigned char* valid) {
  Taps16 t;
  if (!taps16(k, sx, sy, valid, t)) return false;
  const int x_first = _mm_cvtsi128_si32(_mm512_castsi512_si128(t.x0));
  // The upper row: the lower of the first and last pixels' rows (as bilinearRgb8).
  const int y_first = std::min(_mm_cvtsi128_si32(_mm512_castsi512_si128(t.y0)),
                               _mm_extract_epi32(_mm512_extracti32x4_epi32(t.y0, 3), 3));
  const __m512i rel = _mm512_sub_epi32(t.x0, _mm512_set1_epi32(x_first));
  const __m512i dy = _mm512_sub_epi32(t.y0, _mm512_set1_epi32(y_first));
  if (!fits16(k, t, rel, dy, 19)) return false;
  const unsigned char* upper = k.src + static_cast<std::ptrdiff_t>(y_first) * k.src_row + static_cast<std::ptrdiff_t>(x_first) * 6;
  // The lines the group's taps (17 pixels, 102 bytes) occupy prefetchRowsAhead's rows down.
  const char* ahead = reinterpret_cast<const char*>(upper + static_cast<std::ptrdiff_t>(avx2::kPrefetchRows) * k.src_row);
  _mm_prefetch(ahead, _MM_HINT_T0);
  _mm_prefetch(ahead + 64, _MM_HINT_T0);
  _mm_prefetch(ahead + 101, _MM_HINT_T0);
  // Pixels one row down (the group crosses a source row): their upper taps are the lower
  // row's, their lower ones row y_first + 2's (inside: their y0 ≤ h − 2).
  const __mmask16 lower = _mm512_test_epi32_mask(dy, dy);
  __m512i top[2], bottom[2], third[2];
  wordWindow(k, end, upper, top);
  wordWindow(k, end, upper + k.src_row, bottom);
  if (lower) wordWindow(k, end, upper + 2 * k.src_row, third);
  const __m256i left = _mm512_cvtepi32_epi16(_mm512_add_epi32(rel, _mm512_slli_epi32(rel, 1)));  // 3 rel
  const __m512i pair = _mm512_inserti64x4(_mm512_castsi256_si512(left), _mm256_add_epi16(left, _mm256_set1_epi16(3)), 1);
  const __mmask32 lower_words = static_cast<__mmask32>(lower) | (static_cast<__mmask32>(lower) << 16);
  const __m512 full = _mm512_set1_ps(65535.0f), half = _mm512_set1_ps(0.5f);
  __m256i word[3];
  for (int c = 0; c < 3; ++c) {
    const __m512i index = _mm512_add_epi16(pair, _mm512_set1_epi16(static_cast<short>(c)));
    __m512i up = _mm512_permutex2var_epi16(top[0], index, top[1]);
    __m512i down = _mm512_permutex2var_epi16(bottom[0], index, bottom[1]);
    if (lower) {
      up = _mm512_mask_blend_epi16(lower_words, up, down);
      down = _mm512_mask_blend_epi16(lower_words, down, _mm512_permutex2var_epi16(third[0], index, third[1]));
    }
    const __m512 value = bilinearBlend(t.bx0, t.wx1, t.by0, t.wy1, wordsToFloats(_mm512_castsi512_si256(up)),
                                       wordsToFloats(_mm512_extracti64x4_epi64(up, 1)),
                                       wordsToFloats(_mm512_castsi512_si256(down)),
                                       wordsToFloats(_mm512_extracti64x4_epi64(down, 1)));
    // + ½, clamped to [0, 65535], truncated (store<uint16_t>); vpmovdw's truncation is exact.
    word[c] = _mm512_cvtepi32_epi16(
        _mm512_cvttps_epi32(_mm512_min_ps(full, _mm512_max_ps(_mm512_setzero_ps(), _mm512_add_ps(value, half)))));
  }
  // Output word 3 p + c: red p (word p of the first table), green p (16 + p), blue p (32 + p:
  // the second table's word p).
  alignas(64) static constexpr std::uint16_t kInterleave[64] = {
      0,  16, 32, 1,  17, 33, 2,  18, 34, 3,  19, 35, 4,  20, 36, 5,  21, 37, 6,  22, 38, 7,
      23, 39, 8,  24, 40, 9,  25, 41, 10, 26, 42, 11, 27, 43, 12, 28, 44, 13, 29, 45, 14, 30,
      46, 15, 31, 47, 0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0};
  const __m512i rg = _mm512_inserti64x4(_mm512_castsi256_si512(word[0]), word[1], 1);
  const __m512i b = _mm512_castsi256_si512(word[2]);
  _mm512_storeu_si512(o, _mm512_permutex2var_epi16(rg, _mm512_load_si512(kInterleave), b));
  _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(o + 64)),
                      _mm512_castsi512_si256(_mm512_permutex2var_epi16(rg, _mm512_load_si512(kInterleave + 32), b)));
  return true;
}

// The eight pixels of a group that fits (bilinearWideRgb's test) from their windows: `upper`
// the group's first tap in its upper row, `rel3z` 3 × each pixel's column from the first tap
// and `lower` the pixels one row down, both as lanes p and 8 + p; the weights (1 − wx, wx,
// 1 − wy, wy) likewise.
template <class T>
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline void wideEight(const SpanSampler::Context& k, std::int64_t end,
                                                                          unsigned char* o, const unsigned char* upper,
                                                                          __m512i rel3z, __mmask8 lower, __m512 bx0,
                                                                          __m512 bx1, __m512 by0, __m512 by1) {
  // Channel offsets within a pixel's taps: red | green (left; right is + 3), blue left | right.
  const __m512i rg_offset = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1);
  const __m512i b_offset = _mm512_setr_epi32(2, 2, 2, 2, 2, 2, 2, 2, 5, 5, 5, 5, 5, 5, 5, 5);
  const __m512i three = _mm512_set1_epi32(3);
  // Output float 3 p + c: red p (lane p), green p (lane 8 + p) of the first table, blue p
  // (lane p of the second: index 16 + p).
  const __m512i interleave0 = _mm512_setr_epi32(0, 8, 16, 1, 9, 17, 2, 10, 18, 3, 11, 19, 4, 12, 20, 5);
  const __m512i interleave1 = _mm512_setr_epi32(13, 21, 6, 14, 22, 7, 15, 23, 0, 0, 0, 0, 0, 0, 0, 0);
  // As the AVX2 clone: the lines a few rows down (the windows' 128 bytes: three lines).
  const char* ahead = reinterpret_cast<const char*>(upper + static_cast<std::ptrdiff_t>(avx2::kPrefetchRows) * k.src_row);
  _mm_prefetch(ahead, _MM_HINT_T0);
  _mm_prefetch(ahead + 64, _MM_HINT_T0);
  _mm_prefetch(ahead + 127, _MM_HINT_T0);
  __m512 t0, t1, b0, b1;
  sampleWindow<T>(k, end, upper, t0, t1);
  sampleWindow<T>(k, end, upper + k.src_row, b0, b1);
  const __m512i rg_left = _mm512_add_epi32(rel3z, rg_offset), rg_right = _mm512_add_epi32(rg_left, three);
  const __m512i b_index = _mm512_add_epi32(rel3z, b_offset);
  __m512 tl = _mm512_permutex2var_ps(t0, rg_left, t1), tr = _mm512_permutex2var_ps(t0, rg_right, t1);
  __m512 bl = _mm512_permutex2var_ps(b0, rg_left, b1), br = _mm512_permutex2var_ps(b0, rg_right, b1);
  __m512 tb = _mm512_permutex2var_ps(t0, b_index, t1), bb = _mm512_permutex2var_ps(b0, b_index, b1);
  // Pixels one row lower (the group crosses a source row): their upper taps are the lower
  // row's, their lower ones row y_first + 2's (inside: their y0 ≤ h − 2). Lanes p and 8 + p
  // are pixel p in every tap register.
  if (lower) {
    const __mmask16 both = static_cast<__mmask16>(lower | (lower << 8));
    __m512 h0, h1;
    sampleWindow<T>(k, end, upper + 2 * k.src_row, h0, h1);
    tl = _mm512_mask_blend_ps(both, tl, bl);
    tr = _mm512_mask_blend_ps(both, tr, br);
    tb = _mm512_mask_blend_ps(both, tb, bb);
    bl = _mm512_mask_blend_ps(both, bl, _mm512_permutex2var_ps(h0, rg_left, h1));
    br = _mm512_mask_blend_ps(both, br, _mm512_permutex2var_ps(h0, rg_right, h1));
    bb = _mm512_mask_blend_ps(both, bb, _mm512_permutex2var_ps(h0, b_index, h1));
  }
  const __m512 tb_right = _mm512_shuffle_f32x4(tb, tb, 0x4E), bb_right = _mm512_shuffle_f32x4(bb, bb, 0x4E);
  const __m512 rg = bilinearBlend(bx0, bx1, by0, by1, tl, tr, bl, br);
  const __m512 blue = bilinearBlend(bx0, bx1, by0, by1, tb, tb_right, bb, bb_right);
  if constexpr (std::is_same_v<T, float>) {
    float* of = static_cast<float*>(static_cast<void*>(o));
    _mm512_storeu_ps(of, _mm512_permutex2var_ps(rg, interleave0, blue));
    _mm256_storeu_ps(of + 16, _mm512_castps512_ps256(_mm512_permutex2var_ps(rg, interleave1, blue)));
  } else {
    // Every value lies in [0, 65535] after the clamp, so vpmovdw's truncation to words is exact.
    const __m512 full = _mm512_set1_ps(65535.0f), rounding = _mm512_set1_ps(0.5f);
    const __m512i r = _mm512_cvttps_epi32(_mm512_min_ps(full, _mm512_max_ps(_mm512_setzero_ps(), _mm512_add_ps(rg, rounding))));
    const __m512i b = _mm512_cvttps_epi32(_mm512_min_ps(full, _mm512_max_ps(_mm512_setzero_ps(), _mm512_add_ps(blue, rounding))));
    _mm256_storeu_si256(static_cast<__m256i*>(static_cast<void*>(o)), _mm512_cvtepi32_epi16(_mm512_permutex2var_epi32(r, interleave0, b)));
    _mm_storeu_si128(static_cast<__m128i*>(static_cast<void*>(o + 32)),
                     _mm256_castsi256_si128(_mm512_cvtepi32_epi16(_mm512_permutex2var_epi32(r, interleave1, b))));
  }
}

// Sixteen float pixels as two groups of eight that both fit (bilinearWideRgb's test, each eight
// against its own first tap and upper row): the positions, floors, tests and weights worked
// out once on sixteen lanes instead of twice on eight, then each eight from its own windows
// (wideEight), so the same operations per pixel as two eights. Returns false, writing nothing,
// when either eight does not fit (or the image is under 2 × 2).
__attribute__((ARTCAM_AVX512_TARGET, always_inline)) inline bool floatSixteen(const SpanSampler::Context& k,
                                                                             std::int64_t end, unsigned char* o,
                                                                             const float* sx, const float* sy,
                                                                             const unsigned char* valid) {
  Taps16 t;
  if (!taps16(k, sx, sy, valid, t)) return false;
  // Each eight's first tap, and its upper row: the lower of its first and last pixels' rows.
  const __m512i firsts = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 8, 8, 8, 8, 8, 8, 8, 8);
  const __m512i lasts = _mm512_setr_epi32(7, 7, 7, 7, 7, 7, 7, 7, 15, 15, 15, 15, 15, 15, 15, 15);
  const __m512i x_first = _mm512_permutexvar_epi32(firsts, t.x0);
  const __m512i y_first = _mm512_min_epi32(_mm512_permutexvar_epi32(firsts, t.y0), _mm512_permutexvar_epi32(lasts, t.y0));
  const __m512i rel = _mm512_sub_epi32(t.x0, x_first), dy = _mm512_sub_epi32(t.y0, y_first);
  if (!fits16(k, t, rel, dy, 8)) return false;
  const __m512i rel3 = _mm512_add_epi32(rel, _mm512_slli_epi32(rel, 1));
  const __mmask16 lower = _mm512_test_epi32_mask(dy, dy);
  const auto upper = [&k](int x, int y) {
    return k.src + static_cast<std::ptrdiff_t>(y) * k.src_row + static_cast<std::ptrdiff_t>(x) * 12;
  };
  // 0x44: lanes 0–7 in both halves (the first eight); 0xEE: lanes 8–15 (the second).
  wideEight<float>(k, end, o, upper(_mm_cvtsi128_si32(_mm512_castsi512_si128(x_first)), _mm_cvtsi128_si32(_mm512_castsi512_si128(y_first))),
                   _mm512_shuffle_i32x4(rel3, rel3, 0x44), static_cast<__mmask8>(lower), _mm512_shuffle_f32x4(t.bx0, t.bx0, 0x44),
                   _mm512_shuffle_f32x4(t.wx1, t.wx1, 0x44), _mm512_shuffle_f32x4(t.by0, t.by0, 0x44), _mm512_shuffle_f32x4(t.wy1, t.wy1, 0x44));
  wideEight<float>(k, end, o + 96,
                   upper(_mm_cvtsi128_si32(_mm512_extracti32x4_epi32(x_first, 2)), _mm_cvtsi128_si32(_mm512_extracti32x4_epi32(y_first, 2))),
                   _mm512_shuffle_i32x4(rel3, rel3, 0xEE), static_cast<__mmask8>(lower >> 8), _mm512_shuffle_f32x4(t.bx0, t.bx0, 0xEE),
                   _mm512_shuffle_f32x4(t.wx1, t.wx1, 0xEE), _mm512_shuffle_f32x4(t.by0, t.by0, 0xEE), _mm512_shuffle_f32x4(t.wy1, t.wy1, 0xEE));
  return true;
}

// Bilinear float or 16-bit RGB → RGB of the same type (no alpha), eight pixels per group,
// with the AVX2 clone's float operations in its order (each product rounded on its own, as
// roundedProduct), so the tests demand the same bits. Why: the AVX2 clone loads every tap of
// every pixel on its own (32 loads and 16 inserts a group, and for 16-bit widens them one by
// one), which windows avoid.
// Here the group's taps lie within 32 samples (ten pixels) of the upper row and of the lower
// row, loaded once each (sampleWindow) and widened to floats, and vpermt2ps picks them: red and
// green of the left and right taps as four registers (red in lanes 0–7, green in 8–15), blue
// as one per row (left in 0–7, right in 8–15); a group crossing one source row also reads the
// row below and blends. A group wider than the window (minified below 0.9×), one spanning more
// rows, or one touching a border or an invalid pixel runs `fallback` (the AVX2 clone). The
// loads are masked at the image's last sample, so nothing past it is read. 16-bit stores as
// store<uint16_t>: + ½, clamped to [0, 65535], truncated. Sixteen pixels are tried first
// (16-bit: wordGroup16, one channel at a time; float: floatSixteen, the set-up shared by two
// eights); a sixteen that does not fit runs as two eights.
template <class T>
__attribute__((ARTCAM_AVX512_TARGET)) inline long long bilinearWideRgb(const SpanSampler::Context& k,
                                                                       unsigned char* out, int n,
                                                                       const float* sx, const float* sy,
                                                                       const unsigned char* valid,
                                                                       SpanSampler::SpanFn fallback) {
  constexpr int kOutPixel = 3 * static_cast<int>(sizeof(T));
  const __m256 half = _mm256_set1_ps(0.5f), one = _mm256_set1_ps(1.0f);
  const __m256i max_rel = _mm256_set1_epi32(8);
  const __m256i x_limit = _mm256_set1_epi32(k.width - 2), y_limit = _mm256_set1_epi32(k.height - 2);
  const bool sized = k.width >= 2 && k.height >= 2;
  // One past the image's last byte, from its first (row padding after it is not ours).
  const std::int64_t end = static_cast<std::int64_t>(k.height - 1) * k.src_row +
                           static_cast<std::int64_t>(k.width) * kOutPixel;
  long long transparent = 0;
  int i = 0;
  int eights_until = 0;  // after a group of sixteen that did not fit, its two eights
  for (; i + 8 <= n; i += 8) {
    unsigned char* o = out + static_cast<std::ptrdiff_t>(i) * kOutPixel;
    if (i >= eights_until && i + 16 <= n) {
      if (std::is_same_v<T, std::uint16_t> ? wordGroup16(k, end, o, sx + i, sy + i, valid + i)
                                          : floatSixteen(k, end, o, sx + i, sy + i, valid + i)) {
        i += 8;
        continue;
      }
      eights_until = i + 16;
    }
    const __m256 fx = _mm256_sub_ps(_mm256_loadu_ps(sx + i), half);
    const __m256 fy = _mm256_sub_ps(_mm256_loadu_ps(sy + i), half);
    const auto [x0, y0] = avx2::tapFloor(fx, fy);  // the AVX2 clone's integers
    const int x_first = _mm_cvtsi128_si32(_mm256_castsi256_si128(x0));
    // The upper row: the lower of the first and last pixels' rows (as the 8-bit kernel).
    const int y_first = std::min(_mm_cvtsi128_si32(_mm256_castsi256_si128(y0)),
                                 _mm_extract_epi32(_mm256_extracti128_si256(y0, 1), 3));
    const __m256i rel = _mm256_sub_epi32(x0, _mm256_set1_epi32(x_first));
    const __m256i dy = _mm256_sub_epi32(y0, _mm256_set1_epi32(y_first));
    std::uint64_t v;
    std::memcpy(&v, valid + i, 8);
    // Interior (0 ≤ x0 ≤ w − 2, 0 ≤ y0 ≤ h − 2), rows y_first or one below (dy 0 or 1),
    // 0 ≤ rel ≤ 8 (taps in 30 floats).
    // Unsigned, a negative x0 or y0 exceeds any limit (an image under 2 × 2 takes the clone).
    __mmask8 fits = _mm256_cmp_epu32_mask(x0, x_limit, _MM_CMPINT_LE);
    fits = _mm256_mask_cmp_epu32_mask(fits, y0, y_limit, _MM_CMPINT_LE);
    fits = _mm256_mask_cmp_epu32_mask(fits, dy, _mm256_set1_epi32(1), _MM_CMPINT_LE);
    fits = _mm256_mask_cmp_epu32_mask(fits, rel, max_rel, _MM_CMPINT_LE);
    const bool inside = sized && v == 0x0101010101010101ull && fits == 0xFF;
    if (!inside) {
      transparent += fallback(k, o, 8, sx + i, sy + i, valid + i, 1, nullptr);
      continue;
    }
    const unsigned char* upper = k.src + static_cast<std::ptrdiff_t>(y_first) * k.src_row +
                                 static_cast<std::ptrdiff_t>(x_first) * kOutPixel;
    const __m256i rel3 = _mm256_add_epi32(rel, _mm256_slli_epi32(rel, 1));
    const __m256 wx1 = _mm256_sub_ps(fx, _mm256_cvtepi32_ps(x0)), wy1 = _mm256_sub_ps(fy, _mm256_cvtepi32_ps(y0));
    wideEight<T>(k, end, o, upper, _mm512_inserti64x4(_mm512_castsi256_si512(rel3), rel3, 1), _mm256_test_epi32_mask(dy, dy),
                 bothHalves(_mm256_sub_ps(one, wx1)), bothHalves(wx1), bothHalves(_mm256_sub_ps(one, wy1)), bothHalves(wy1));
  }
  if (i < n)
    transparent += fallback(k, out + static_cast<std::ptrdiff_t>(i) * kOutPixel, n - i, sx + i, sy + i, valid + i, 1, nullptr);
  return transparent;
}

#undef ARTCAM_AVX512_TARGET

}  // namespace artcam::avx512

#pragma GCC diagnostic pop

#endif
