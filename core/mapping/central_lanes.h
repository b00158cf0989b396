// SPDX-License-Identifier: Apache-2.0
// What the central inverse's two forms (central_inverse.h) share in their spans: the scalar
// loop over a span's pixels, and in SIMD lanes a group's stores from its failed lanes.
#pragma once

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>
#endif

namespace artcam::central_lanes {

// Pixels x0 + i, i0 ≤ i < n, each from solve(t.x, u, v) (false: no preimage, position 0).
template <class Solve>
inline void spanPixels(int x0, int i0, int n, float* sx, float* sy, unsigned char* valid, const Solve& solve) {
  for (int i = i0; i < n; ++i) {
    double u = 0.0, v = 0.0;
    const bool ok = solve(x0 + i + 0.5, u, v);
    sx[i] = ok ? static_cast<float>(u) : 0.0f;
    sy[i] = ok ? static_cast<float>(v) : 0.0f;
    valid[i] = ok ? 1 : 0;
  }
}

#if defined(__x86_64__)

// valid[i … i + 3] as one little-endian word, from the lanes that failed (bit k: lane k).
constexpr std::uint32_t kValidBytes[16] = {
    0x01010101u, 0x01010100u, 0x01010001u, 0x01010000u, 0x01000101u, 0x01000100u, 0x01000001u, 0x01000000u,
    0x00010101u, 0x00010100u, 0x00010001u, 0x00010000u, 0x00000101u, 0x00000100u, 0x00000001u, 0x00000000u};

// GCC 12 reports its own AVX-512 intrinsics' undefined-vector idiom as maybe uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// Lanes whose sign bit is set.
__attribute__((target("avx512f"), always_inline)) inline __mmask8 negative(__m512i v) {
  return _mm512_cmplt_epi64_mask(v, _mm512_setzero_si512());
}

// Eight pixels' positions, 0 and not valid where `bad` has the lane.
__attribute__((target("avx512f"), always_inline)) inline void storeEight(__m512d u, __m512d v, __mmask8 bad, float* sx,
                                                                      float* sy, unsigned char* valid) {
  const __mmask8 good = static_cast<__mmask8>(~bad);
  _mm256_storeu_ps(sx, _mm512_cvtpd_ps(_mm512_maskz_mov_pd(good, u)));
  _mm256_storeu_ps(sy, _mm512_cvtpd_ps(_mm512_maskz_mov_pd(good, v)));
  const std::uint32_t lo = kValidBytes[bad & 15], hi = kValidBytes[bad >> 4];
  std::memcpy(valid, &lo, 4);
  std::memcpy(valid + 4, &hi, 4);
}
#pragma GCC diagnostic pop

// Four pixels' positions, 0 and not valid where `bad`'s lane has its sign bit set.
__attribute__((target("avx2"), always_inline)) inline void storeFour(__m256d u, __m256d v, __m256d bad, float* sx,
                                                                    float* sy, unsigned char* valid) {
  const __m256d zero = _mm256_setzero_pd();
  _mm_storeu_ps(sx, _mm256_cvtpd_ps(_mm256_blendv_pd(u, zero, bad)));
  _mm_storeu_ps(sy, _mm256_cvtpd_ps(_mm256_blendv_pd(v, zero, bad)));
  const std::uint32_t good = kValidBytes[_mm256_movemask_pd(bad)];
  std::memcpy(valid, &good, 4);
}
#endif

}  // namespace artcam::central_lanes
