// SPDX-License-Identifier: Apache-2.0
// What the central inverse's SIMD lanes (both forms, central_inverse.h) share: a group's valid
// bytes from its failed lanes, and the lanes whose sign bit is set.
#pragma once

#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

namespace artcam::central_lanes {

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
#pragma GCC diagnostic pop

}  // namespace artcam::central_lanes
#endif
