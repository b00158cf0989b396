// SPDX-License-Identifier: Apache-2.0
// The rational kernel's AVX-512 lanes (certified cells, sixteen pixels a step), included by
// rational_kernel.cpp alone after rational_kernel_avx2.h; chosen at construction through
// core/util/cpu_features.h when CoordinateOptions::allow_avx512 is set.
#pragma once

#pragma GCC diagnostic push
// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*() (a self-initialised variable):
// a false positive of both warnings.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
__attribute__((target("avx512f,avx512vl,fma"))) void polyCellsAvx512(const CellPoly* cells, int count, float v,
                                                                    float* sx, float* sy) {
  const __m256 vv = _mm256_set1_ps(v);
  for (int cell = 0; cell < count; ++cell, sx += kCellPixels, sy += kCellPixels) {
    const CellPoly& c = cells[cell];
    const __m512 k = _mm512_castps256_ps512(_mm256_fmadd_ps(
        vv, _mm256_fmadd_ps(vv, _mm256_fmadd_ps(vv, _mm256_load_ps(c.p[3]), _mm256_load_ps(c.p[2])), _mm256_load_ps(c.p[1])),
        _mm256_load_ps(c.p[0])));
    const __m512 x0 = _mm512_permutexvar_ps(_mm512_set1_epi32(0), k), x1 = _mm512_permutexvar_ps(_mm512_set1_epi32(1), k),
                 x2 = _mm512_permutexvar_ps(_mm512_set1_epi32(2), k), x3 = _mm512_permutexvar_ps(_mm512_set1_epi32(3), k);
    const __m512 y0 = _mm512_permutexvar_ps(_mm512_set1_epi32(4), k), y1 = _mm512_permutexvar_ps(_mm512_set1_epi32(5), k),
                 y2 = _mm512_permutexvar_ps(_mm512_set1_epi32(6), k), y3 = _mm512_permutexvar_ps(_mm512_set1_epi32(7), k);
    const __m512 ax = _mm512_set1_ps(c.anchor_x), ay = _mm512_set1_ps(c.anchor_y);
#pragma GCC unroll 2
    for (int g = 0; g < kCellPixels / 16; ++g) {
      const __m512 w = _mm512_load_ps(kCellU.u + 16 * g);
      const __m512 px = _mm512_fmadd_ps(w, _mm512_fmadd_ps(w, _mm512_fmadd_ps(w, x3, x2), x1), x0);
      const __m512 py = _mm512_fmadd_ps(w, _mm512_fmadd_ps(w, _mm512_fmadd_ps(w, y3, y2), y1), y0);
      _mm512_storeu_ps(sx + 16 * g, _mm512_add_ps(ax, px));
      _mm512_storeu_ps(sy + 16 * g, _mm512_add_ps(ay, py));
    }
  }
}
#pragma GCC diagnostic pop
