// SPDX-License-Identifier: Apache-2.0
// The interior of the 8-bit bicubic sampler (span_sampler.cpp only; SIMD where it
// pays): a pixel whose 4 × 4 taps are all inside the source, in float, rows first:
//   V_i = ((wy0 p0i + wy1 p1i) + wy2 p2i) + wy3 p3i   (tap column i, each channel),
//   out = (wx0 V_0 + wx2 V_2) + (wx1 V_1 + wx3 V_3),
// with sampling.h's Keys weights (a = −0.5) from cubicWeightsU8. The portable code and the
// AVX2 clone do these operations in this order (no FMA in either), so they agree bit for bit
// and the tests demand it; the border pixels keep the general float taps.
//
// The AVX2 clone does one pixel at a time across its taps and channels: each row's four taps
// come in with one 16-byte load, spread to (R, G, B, 0) per tap, even taps in the low 128-bit
// lane and odd ones in the high lane, so the four rows are eight multiply-adds on 256 bits
// and the columns two more. RGB's load reads four bytes past the last tap: such a pixel must
// not have its lowest tap row on the image's last row (CubicInterior::fits).
#pragma once

#include "core/sampling/span_sampler.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <cstdint>
#include <cstring>

namespace artcam::cubic {

// Keys weights (a = −0.5) for offset t in [0, 1), as sampling.h's, in float.
[[gnu::always_inline]] inline void cubicWeightsU8(float t, float w[4]) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = -0.5f * t3 + t2 - 0.5f * t;
  w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
  w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
  w[3] = 0.5f * t3 - 0.5f * t2;
}

// A pixel's top-left tap and weights, and whether all its taps are inside (plus, for RGB, one
// row of margin for the 16-byte loads). fx, fy: the position in pixel-centre-at-integer terms.
struct CubicInterior {
  int x0 = 0, y0 = 0;
  float wx[4], wy[4];
  template <int C>
  [[gnu::always_inline]] bool fits(const SpanSampler::Context& k, float fx, float fy) {
    if (!(fx > -2.0f && fx < k.width + 1.0f && fy > -2.0f && fy < k.height + 1.0f)) return false;
    const int ix = static_cast<int>(fx + 2.0f) - 2, iy = static_cast<int>(fy + 2.0f) - 2;
    x0 = ix - 1;
    y0 = iy - 1;
    if (!(x0 >= 0 && y0 >= 0 && x0 + 3 < k.width && y0 + 3 < k.height - (C == 3 ? 1 : 0))) return false;
    cubicWeightsU8(fx - static_cast<float>(ix), wx);
    cubicWeightsU8(fy - static_cast<float>(iy), wy);
    return true;
  }
};

// The portable interior: v[c] for the C channels.
template <int C>
[[gnu::always_inline]] inline void interiorScalar(const SpanSampler::Context& k, const CubicInterior& p,
                                                  float v[4]) {
  float col[4][4];  // [tap i][channel]
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < C; ++c) {
      const std::uint8_t* r = k.src + static_cast<std::ptrdiff_t>(p.y0) * k.src_row + (p.x0 + i) * C + c;
      float acc = p.wy[0] * static_cast<float>(r[0]);
      acc = acc + p.wy[1] * static_cast<float>(r[k.src_row]);
      acc = acc + p.wy[2] * static_cast<float>(r[2 * k.src_row]);
      acc = acc + p.wy[3] * static_cast<float>(r[3 * k.src_row]);
      col[i][c] = acc;
    }
  for (int c = 0; c < C; ++c)
    v[c] = (p.wx[0] * col[0][c] + p.wx[2] * col[2][c]) + (p.wx[1] * col[1][c] + p.wx[3] * col[3][c]);
}

#if defined(__x86_64__) || defined(__i386__)
#define ARTCAM_HAVE_AVX2_CUBIC 1
// The interior in AVX2 (operations as interiorScalar's). Writes the pixel's bytes as the scalar code stores them (⌊clamp(v + 0.5, 0, 255)⌋; alpha 255
// appended when A), four bytes when `spare` says the byte after an RGB pixel may be written
// (the next pixel's); returns v of the source's alpha channel (1 without one) for the count
// of transparent pixels. In registers throughout: storing v and reading it back per channel
// stalls on store forwarding.
template <int C, bool A>
__attribute__((target("avx2"))) inline float interiorAvx2(const SpanSampler::Context& k, const CubicInterior& p,
                                                        std::uint8_t* out, bool spare) {
  static_assert(C == 3 || C == 4);
  // Taps (0, 1, 2, 3) → bytes [tap 0 RGB(A) | tap 1 | tap 2 | tap 3], four bytes each.
  const __m128i spread = C == 4 ? _mm_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)
                                : _mm_setr_epi8(0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1);
  const std::uint8_t* r = k.src + static_cast<std::ptrdiff_t>(p.y0) * k.src_row + p.x0 * C;
  // The line this pixel's taps start on, seven rows down: the first of the four rows the same
  // span reads about four output rows later (the span-major walk of warp.cpp; as
  // span_sampler_avx2.h's prefetchRowsAhead). A prefetch never faults; the address is formed
  // as an integer so no pointer leaves the image.
  _mm_prefetch(reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(r) +
                                             static_cast<std::uintptr_t>(7 * k.src_row)), _MM_HINT_T0);
  __m256 even_odd = _mm256_setzero_ps(), later = _mm256_setzero_ps();  // taps (0 | 1), (2 | 3)
  for (int j = 0; j < 4; ++j, r += k.src_row) {
    const __m128i bytes = _mm_shuffle_epi8(_mm_loadu_si128(static_cast<const __m128i*>(static_cast<const void*>(r))), spread);
    const __m256 t01 = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(bytes));
    const __m256 t23 = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_srli_si128(bytes, 8)));
    const __m256 w = _mm256_set1_ps(p.wy[j]);
    if (j == 0) {
      even_odd = _mm256_mul_ps(w, t01);
      later = _mm256_mul_ps(w, t23);
    } else {
      even_odd = _mm256_add_ps(even_odd, _mm256_mul_ps(w, t01));
      later = _mm256_add_ps(later, _mm256_mul_ps(w, t23));
    }
  }
  const __m256 w01 = _mm256_setr_m128(_mm_set1_ps(p.wx[0]), _mm_set1_ps(p.wx[1]));
  const __m256 w23 = _mm256_setr_m128(_mm_set1_ps(p.wx[2]), _mm_set1_ps(p.wx[3]));
  // Low lane: wx0 V0 + wx2 V2, high lane: wx1 V1 + wx3 V3; then their sum.
  const __m256 s = _mm256_add_ps(_mm256_mul_ps(w01, even_odd), _mm256_mul_ps(w23, later));
  const __m128 v = _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps(s, 1));
  const __m128 clamped = _mm_min_ps(_mm_max_ps(_mm_add_ps(v, _mm_set1_ps(0.5f)), _mm_setzero_ps()),
                                    _mm_set1_ps(255.0f));
  const __m128i q = _mm_cvttps_epi32(clamped);
  std::uint32_t word = static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_packus_epi16(_mm_packus_epi32(q, q), q)));
  if constexpr (A) word |= 0xFF000000u;
  if (C == 4 || A || spare) {
    std::memcpy(out, &word, 4);
  } else {
    const std::uint16_t low = static_cast<std::uint16_t>(word);
    std::memcpy(out, &low, 2);
    out[2] = static_cast<std::uint8_t>(word >> 16);
  }
  if (k.src_alpha < 0) return 1.0f;
  return _mm_cvtss_f32(_mm_permutevar_ps(v, _mm_set1_epi32(k.src_alpha)));
}
#endif

}  // namespace artcam::cubic
