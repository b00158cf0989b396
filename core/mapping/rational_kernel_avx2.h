// SPDX-License-Identifier: Apache-2.0
// The rational kernel's AVX2 (and FMA) lanes, included by rational_kernel.cpp alone, inside its
// anonymous namespace: each function carries its ISA as __attribute__((target(…))) and the
// kernel picks one at construction through core/util/cpu_features.h (the project's one SIMD
// convention: no -march flag, no target_clones). Every lane computes the portable loop's bits.
#pragma once

// The seed check's lanes with AVX2 (four doubles at once): checkSpanBody compiled for the ISA,
// so the same operations in the same order as checkSpanScalar, no FMA in either: the same bits.
__attribute__((target("avx2"))) void checkSpanAvx2(const CheckInputs& in, double tx0, double ty,
                                                   const double* bx, const double* by, double* qx,
                                                   double* qy, std::int64_t* passed) {
  checkSpanBody(in, tx0, ty, bx, by, qx, qy, passed);
}

// The scalar cell and square loops with the FMA instruction (std::fma inlined as vfmadd):
// the same bits as polyCellScalar and polySquareScalar, which call the library's fma.
__attribute__((target("fma"))) void polyCellFma(const CellPoly& c, float v, float* sx, float* sy) {
  polyCellBody(c, v, sx, sy);
}

__attribute__((target("fma"))) void polySquareFma(const CellPoly& c, float v, float scale, int j0,
                                                  int count, float* sx, float* sy) {
  polySquareBody(c, v, scale, j0, count, sx, sy);
}

// A patch's row v, by Horner in v over its eight lanes, as broadcast coefficients of the cubic
// in u (x: x0 … x3, y: y0 … y3) with the anchor: the cells' and the squares' AVX2 kernels.
// Named, not arrays: GCC keeps an array of vectors on the stack.
struct RowCubicAvx2 {
  __m256 x0, x1, x2, x3, y0, y1, y2, y3, ax, ay;
};

__attribute__((target("avx2,fma"), always_inline)) inline RowCubicAvx2 rowCubicAvx2(const CellPoly& c, __m256 vv) {
  const __m256 k = _mm256_fmadd_ps(
      vv, _mm256_fmadd_ps(vv, _mm256_fmadd_ps(vv, _mm256_load_ps(c.p[3]), _mm256_load_ps(c.p[2])), _mm256_load_ps(c.p[1])),
      _mm256_load_ps(c.p[0]));
  // (A lambda here would not inherit the target: GCC would refuse to inline the intrinsics.)
  return {_mm256_permutevar8x32_ps(k, _mm256_set1_epi32(0)), _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(1)),
          _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(2)), _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(3)),
          _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(4)), _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(5)),
          _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(6)), _mm256_permutevar8x32_ps(k, _mm256_set1_epi32(7)),
          _mm256_set1_ps(c.anchor_x), _mm256_set1_ps(c.anchor_y)};
}

// Eight pixels at u = w of the row.
__attribute__((target("avx2,fma"), always_inline)) inline void storeRowCubicAvx2(const RowCubicAvx2& r, __m256 w,
                                                                                float* sx, float* sy) {
  const __m256 px = _mm256_fmadd_ps(w, _mm256_fmadd_ps(w, _mm256_fmadd_ps(w, r.x3, r.x2), r.x1), r.x0);
  const __m256 py = _mm256_fmadd_ps(w, _mm256_fmadd_ps(w, _mm256_fmadd_ps(w, r.y3, r.y2), r.y1), r.y0);
  _mm256_storeu_ps(sx, _mm256_add_ps(r.ax, px));
  _mm256_storeu_ps(sy, _mm256_add_ps(r.ay, py));
}

__attribute__((target("avx2,fma"))) void polyCellsAvx2(const CellPoly* cells, int count, float v, float* sx,
                                                       float* sy) {
  const __m256 vv = _mm256_set1_ps(v);
  for (int cell = 0; cell < count; ++cell, sx += kCellPixels, sy += kCellPixels) {
    const RowCubicAvx2 r = rowCubicAvx2(cells[cell], vv);
#pragma GCC unroll 4
    for (int g = 0; g < kCellPixels / 8; ++g) storeRowCubicAvx2(r, _mm256_load_ps(kCellU.u + 8 * g), sx + 8 * g, sy + 8 * g);
  }
}

__attribute__((target("avx2,fma"))) void polySquareAvx2(const CellPoly& c, float v, float scale, int j0,
                                                        int count, float* sx, float* sy) {
  const RowCubicAvx2 r = rowCubicAvx2(c, _mm256_set1_ps(v));
  const __m256 half = _mm256_set1_ps(0.5f), sc = _mm256_set1_ps(scale);
  int g = 0;
  for (; g + 8 <= count; g += 8) {
    const __m256 j = _mm256_cvtepi32_ps(
        _mm256_add_epi32(_mm256_set1_epi32(j0 + g), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
    storeRowCubicAvx2(r, _mm256_mul_ps(_mm256_add_ps(j, half), sc), sx + g, sy + g);
  }
  if (g < count) polySquareBody(c, v, scale, j0 + g, count - g, sx + g, sy + g);
}
