// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/central_inverse.h"

#include "core/model/structure.h"
#include "core/mapping/central_lanes.h"
#include "core/util/cpu_features.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <vector>

namespace artcam {
namespace {

// Factors below this (relative to the forms scaled to 1 in the unit frame) count as zero, and
// the factorisation must reproduce the map to this share of its frame.
constexpr double kRelativeTolerance = 1e-9;

// Q = sym(l hᵀ) + c D: the h and c that fit best (6 equations, the upper triangle), and the
// largest residual.
double fitFactor(const Eigen::Matrix3d& q, const Eigen::Vector3d& l, const Eigen::Matrix3d& d,
                 Eigen::Vector3d& h, double& c) {
  Eigen::Matrix<double, 6, 4> a = Eigen::Matrix<double, 6, 4>::Zero();
  Eigen::Matrix<double, 6, 1> b;
  int row = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j, ++row) {
      // (l_i h_j + l_j h_i) / 2 + c d_ij = q_ij
      a(row, j) += 0.5 * l(i);
      a(row, i) += 0.5 * l(j);
      a(row, 3) = d(i, j);
      b(row) = q(i, j);
    }
  const Eigen::Vector4d x = a.colPivHouseholderQr().solve(b);
  h = x.head<3>();
  c = x(3);
  return (a * x - b).cwiseAbs().maxCoeff();
}

}  // namespace

std::optional<CentralInverse> CentralInverse::detect(const RationalMap& forward, FrameSize source_px,
                                                     const CentreReference& centre) {
  if (forward.stageCount() != 1 || source_px.width <= 0 || source_px.height <= 0) return std::nullopt;
  const std::vector<Eigen::Matrix3d>& q = forward.stage(0);
  // A unit frame on both sides, so that the forms' entries are comparable: s = N s′ with s′
  // in [−1, 1] across the source's larger side, and outputs measured from the centre's image in
  // the same unit.
  const double sigma = 0.5 * std::max(source_px.width, source_px.height);
  Eigen::Matrix3d n = Eigen::Matrix3d::Identity();
  n(0, 0) = n(1, 1) = sigma;
  n(0, 2) = 0.5 * source_px.width;
  n(1, 2) = 0.5 * source_px.height;
  const Eigen::Vector2d reference = centre.target;
  std::array<Eigen::Matrix3d, 3> u;
  for (int k = 0; k < 3; ++k) u[k] = n.transpose() * q[k] * n;
  u[0] = (u[0] - reference.x() * u[2]) / sigma;
  u[1] = (u[1] - reference.y() * u[2]) / sigma;
  double scale = 0.0;
  for (const Eigen::Matrix3d& m : u) scale = std::max(scale, m.cwiseAbs().maxCoeff());
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
  for (Eigen::Matrix3d& m : u) m /= scale;

  // c_t's first coordinate makes u₀ − c u₂ a product of two lines: a real root of
  // det(u₀ − c u₂) = 0, a generalised eigenvalue.
  const Eigen::GeneralizedEigenSolver<Eigen::Matrix3d> pencil(u[0], u[2], false);
  for (int r = 0; r < 3 && pencil.info() == Eigen::Success; ++r) {
    const std::complex<double> alpha = pencil.alphas()(r);
    const double beta_r = pencil.betas()(r);
    if (std::abs(beta_r) < kRelativeTolerance || std::abs(alpha.imag()) > kRelativeTolerance * std::abs(beta_r))
      continue;
    const Eigen::Matrix3d m = u[0] - (alpha.real() / beta_r) * u[2];
    // Its lines (structure.h, as a homography's denominator's), to the forms' unit scale.
    const std::vector<Eigen::VectorXd> lines = realLineFactors(m, kRelativeTolerance);
    for (const Eigen::Vector3d l : lines) {
      Eigen::Vector3d h0, h1;
      double c0 = 0.0, c1 = 0.0;
      if (fitFactor(u[0], l, u[2], h0, c0) > kRelativeTolerance ||
          fitFactor(u[1], l, u[2], h1, c1) > kRelativeTolerance)
        continue;
      Eigen::Matrix<double, 2, 3> h_unit;
      h_unit.row(0) = h0.transpose();
      h_unit.row(1) = h1.transpose();
      if (!(std::abs(h_unit.leftCols<2>().determinant()) > kRelativeTolerance)) continue;
      // Back to pixels: s′ = N⁻¹ s, F = reference + σ F′.
      const Eigen::Matrix3d n_inv = n.inverse();
      const Eigen::Matrix<double, 2, 3> h = sigma * h_unit * n_inv;
      const Eigen::Vector3d l_px = n_inv.transpose() * l;
      const Eigen::Matrix3d q_px = n_inv.transpose() * u[2] * n_inv;
      CentralInverse out;
      Rows& w = out.rows_;
      w.ct = reference + sigma * Eigen::Vector2d(c0, c1);
      const Eigen::Matrix2d h2 = h.leftCols<2>();
      const Eigen::Matrix2d e = h2.inverse();
      const Eigen::Vector2d cs = -e * h.col(2);
      const Eigen::Vector3d cs_h(cs.x(), cs.y(), 1.0);
      w.e00 = e(0, 0), w.e01 = e(0, 1), w.e10 = e(1, 0), w.e11 = e(1, 1);
      w.lax = l_px(0), w.lay = l_px(1);
      const Eigen::Vector3d qc = q_px * cs_h;
      w.mx = qc(0), w.my = qc(1);
      w.qxx = q_px(0, 0), w.qxy = q_px(0, 1), w.qyy = q_px(1, 1);
      w.beta = l_px.dot(cs_h);
      w.c = cs_h.dot(qc);
      w.csx = cs.x(), w.csy = cs.y();
      w.det_h_positive = h2.determinant() > 0.0;
      w.den_negative = (centre.denominator_signs & 1u) != 0;
      w.det_positive = centre.det_positive;
      if (!(std::abs(w.beta) > 0.0) || !(std::abs(w.c) > 0.0)) continue;
      // The factorisation must be the map: compare at a grid over the source frame.
      bool same = true;
      constexpr int kGrid = 9;
      for (int j = 0; j < kGrid && same; ++j)
        for (int i = 0; i < kGrid && same; ++i) {
          const Eigen::Vector2d s(source_px.width * i / (kGrid - 1.0), source_px.height * j / (kGrid - 1.0));
          Eigen::Vector2d f;
          if (!forward.evaluate(s, f, nullptr)) continue;
          const Eigen::Vector3d sh(s.x(), s.y(), 1.0);
          const double den = sh.dot(q_px * sh);
          const Eigen::Vector2d g = w.ct + h * sh * (l_px.dot(sh) / den);
          same = (f - g).norm() <= kRelativeTolerance * (sigma + (f - reference).norm());
        }
      if (same) return out;
    }
  }
  // No finite target centre: perhaps one at infinity.
  return detectParallel(forward, source_px, centre, u, n, sigma);
}

namespace {

// A row's quantities as polynomials in dx = t.x − c_t.x (evaluated per pixel, so nothing
// accumulates along the row): p₁ = β − 2B and α linear, p₂ = α − A quadratic, e linear.
struct RowPolys {
  double p1_0, p1_1;        // p₁ = p1_0 + p1_1 dx
  double al_0, al_1;        // α = al_0 + al_1 dx
  double p2_0, p2_1, p2_2;  // p₂ = p2_0 + dx (p2_1 + dx p2_2)
  double ex_0, ex_1, ey_0, ey_1;
  double two_c, beta, csx, csy;
  double ctx;  // dx = t.x − ctx, t.x = x + 0.5 exact: one rounding, the same in every lane
  // Sign bits a solution must match (see the header): sb(p₁) ⊕ sb(n) = fold_bit (the near
  // root's P′ has p₁'s sign), sb(μ) ⊕ sb(n) = side_bit (the denominator μ n).
  bool fold_bit, side_bit;
};

// The row through output ordinate ty.
RowPolys rowPolys(const CentralInverse::Rows& w, double ty) {
  RowPolys r{};
  const double dy = ty - w.ct.y();
  r.ex_0 = w.e01 * dy, r.ex_1 = w.e00;
  r.ey_0 = w.e11 * dy, r.ey_1 = w.e10;
  r.al_0 = w.lax * r.ex_0 + w.lay * r.ey_0, r.al_1 = w.lax * r.ex_1 + w.lay * r.ey_1;
  const double b0 = w.mx * r.ex_0 + w.my * r.ey_0, b1 = w.mx * r.ex_1 + w.my * r.ey_1;
  r.p1_0 = w.beta - 2.0 * b0, r.p1_1 = -2.0 * b1;
  // A = eᵀ Q₂ e with e = e₀ + dx e₁.
  const double a0 = w.qxx * r.ex_0 * r.ex_0 + 2.0 * w.qxy * r.ex_0 * r.ey_0 + w.qyy * r.ey_0 * r.ey_0;
  const double a1 = 2.0 * (w.qxx * r.ex_0 * r.ex_1 + w.qxy * (r.ex_0 * r.ey_1 + r.ey_0 * r.ex_1) +
                           w.qyy * r.ey_0 * r.ey_1);
  const double a2 = w.qxx * r.ex_1 * r.ex_1 + 2.0 * w.qxy * r.ex_1 * r.ey_1 + w.qyy * r.ey_1 * r.ey_1;
  r.p2_0 = r.al_0 - a0, r.p2_1 = r.al_1 - a1, r.p2_2 = -a2;
  r.two_c = 2.0 * w.c, r.beta = w.beta, r.csx = w.csx, r.csy = w.csy;
  r.ctx = w.ct.x();
  r.fold_bit = w.det_positive != w.det_h_positive;  // sb(det J) = sb(det H₂) ⊕ sb(P′) ⊕ sb(n)
  r.side_bit = w.den_negative;
  return r;
}

// Positions beyond this many pixels (in μ, whose unit is |e| ≤ a frame) are no preimage: they
// would overflow float or sample nothing.
constexpr double kMaxMu = 1e15;

bool signBit(double v) { return std::signbit(v); }

// Output point (tx, the row's ty): the near root −2C / (p₁ + sgn(p₁) √D) (the stable form,
// finite where p₂ → 0 near c_t), and where it fails the tests the far one. The vector code
// computes the near root by the same operations in the same order (no FMA): the same bits.
bool solvePixel(const RowPolys& r, double tx, double& u, double& v) {
  const double dx = tx - r.ctx;
  const double p1 = r.p1_0 + r.p1_1 * dx;
  const double al = r.al_0 + r.al_1 * dx;
  const double p2 = r.p2_0 + dx * (r.p2_1 + dx * r.p2_2);
  const double disc = p1 * p1 + r.two_c * 2.0 * p2;
  const double root = std::sqrt(disc > 0.0 ? disc : 0.0);  // as _mm256_max_pd: 0 for NaN
  const double mu = r.two_c / (p1 + std::copysign(root, p1));
  const double n = mu * al + r.beta;
  const bool near_ok = !signBit(disc) & ((signBit(p1) ^ signBit(n)) == r.fold_bit) &
                       ((signBit(mu) ^ signBit(n)) == r.side_bit) & (std::abs(mu) < kMaxMu);
  double m = mu;
  if (!near_ok) {
    // The far root q / p₂, q = −(p₁ + sgn(p₁) √D) / 2; its P′ has the opposite sign.
    if (signBit(disc)) return false;
    const double far = -0.5 * (p1 + std::copysign(root, p1)) / p2;
    const double nf = far * al + r.beta;
    if (!(((signBit(p1) ^ signBit(nf)) != r.fold_bit) & ((signBit(far) ^ signBit(nf)) == r.side_bit) &
          (std::abs(far) < kMaxMu)))
      return false;
    m = far;
  }
  const double ex = r.ex_0 + r.ex_1 * dx, ey = r.ey_0 + r.ey_1 * dx;
  u = r.csx + m * ex;
  v = r.csy + m * ey;
  return true;
}

// Pixels x0 + i, i0 ≤ i < n.
void spanScalar(const RowPolys& r, int x0, int i0, int n, float* sx, float* sy, unsigned char* valid) {
  central_lanes::spanPixels(x0, i0, n, sx, sy, valid,
                            [&r](double tx, double& u, double& v) { return solvePixel(r, tx, u, v); });
}

#if defined(__x86_64__)
using central_lanes::negative;
using central_lanes::storeEight;
using central_lanes::storeFour;

// solvePixel's near root in four lanes. A lane with no root (D < 0) is written empty; a group
// with a lane whose near root fails the tests where D ≥ 0 (the far root may be its preimage)
// is redone by solvePixel.
__attribute__((target("avx2"))) void spanAvx2(const RowPolys& r, int x0, int n, float* sx, float* sy,
                                              unsigned char* valid) {
  const __m256d zero = _mm256_setzero_pd(), two = _mm256_set1_pd(2.0), sign = _mm256_set1_pd(-0.0);
  const __m256d max_mu = _mm256_set1_pd(kMaxMu);
  const __m256d p1_0 = _mm256_set1_pd(r.p1_0), p1_1 = _mm256_set1_pd(r.p1_1);
  const __m256d al_0 = _mm256_set1_pd(r.al_0), al_1 = _mm256_set1_pd(r.al_1);
  const __m256d p2_0 = _mm256_set1_pd(r.p2_0), p2_1 = _mm256_set1_pd(r.p2_1), p2_2 = _mm256_set1_pd(r.p2_2);
  const __m256d ex_0 = _mm256_set1_pd(r.ex_0), ex_1 = _mm256_set1_pd(r.ex_1);
  const __m256d ey_0 = _mm256_set1_pd(r.ey_0), ey_1 = _mm256_set1_pd(r.ey_1);
  const __m256d two_c = _mm256_set1_pd(r.two_c), beta = _mm256_set1_pd(r.beta);
  const __m256d csx = _mm256_set1_pd(r.csx), csy = _mm256_set1_pd(r.csy), ctx = _mm256_set1_pd(r.ctx);
  const __m256d fold_bit = r.fold_bit ? sign : zero, side_bit = r.side_bit ? sign : zero;
  const __m256d lanes = _mm256_setr_pd(0.0, 1.0, 2.0, 3.0);
  const int whole = n / 4 * 4;
  for (int i = 0; i < whole; i += 4) {
    const __m256d dx = _mm256_sub_pd(_mm256_add_pd(_mm256_set1_pd(x0 + i + 0.5), lanes), ctx);
    const __m256d p1 = _mm256_add_pd(p1_0, _mm256_mul_pd(p1_1, dx));
    const __m256d al = _mm256_add_pd(al_0, _mm256_mul_pd(al_1, dx));
    const __m256d p2 = _mm256_add_pd(p2_0, _mm256_mul_pd(dx, _mm256_add_pd(p2_1, _mm256_mul_pd(dx, p2_2))));
    const __m256d disc = _mm256_add_pd(_mm256_mul_pd(p1, p1), _mm256_mul_pd(_mm256_mul_pd(two_c, two), p2));
    const __m256d root = _mm256_sqrt_pd(_mm256_max_pd(disc, zero));
    const __m256d mu = _mm256_div_pd(two_c, _mm256_add_pd(p1, _mm256_or_pd(root, _mm256_and_pd(sign, p1))));
    const __m256d nn = _mm256_add_pd(_mm256_mul_pd(mu, al), beta);
    // Sign bit set where a test fails.
    const __m256d bad = _mm256_or_pd(
        _mm256_or_pd(disc, _mm256_cmp_pd(_mm256_andnot_pd(sign, mu), max_mu, _CMP_NLT_UQ)),
        _mm256_or_pd(_mm256_xor_pd(_mm256_xor_pd(p1, nn), fold_bit), _mm256_xor_pd(_mm256_xor_pd(mu, nn), side_bit)));
    const int bad_bits = _mm256_movemask_pd(bad);
    // A lane with D ≥ 0 whose near root failed may have the far one.
    if (bad_bits & ~_mm256_movemask_pd(disc)) {
      spanScalar(r, x0, i, i + 4, sx, sy, valid);
      continue;
    }
    const __m256d u = _mm256_add_pd(csx, _mm256_mul_pd(mu, _mm256_add_pd(ex_0, _mm256_mul_pd(ex_1, dx))));
    const __m256d v = _mm256_add_pd(csy, _mm256_mul_pd(mu, _mm256_add_pd(ey_0, _mm256_mul_pd(ey_1, dx))));
    // No root (D < 0): position 0, as the scalar code writes.
    storeFour(u, v, bad, sx + i, sy + i, valid + i);
  }
  spanScalar(r, x0, whole, n, sx, sy, valid);
}

// GCC 12 reports its own AVX-512 intrinsics' undefined-vector idiom as maybe uninitialised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// spanAvx2 in eight lanes.
__attribute__((target("avx512f"))) void spanAvx512(const RowPolys& r, int x0, int n, float* sx, float* sy,
                                                   unsigned char* valid) {
  const __m512d zero = _mm512_setzero_pd(), two = _mm512_set1_pd(2.0);
  const __m512i sign = _mm512_set1_epi64(std::int64_t{1} << 63), izero = _mm512_setzero_si512();
  const __m512d max_mu = _mm512_set1_pd(kMaxMu);
  const __m512d p1_0 = _mm512_set1_pd(r.p1_0), p1_1 = _mm512_set1_pd(r.p1_1);
  const __m512d al_0 = _mm512_set1_pd(r.al_0), al_1 = _mm512_set1_pd(r.al_1);
  const __m512d p2_0 = _mm512_set1_pd(r.p2_0), p2_1 = _mm512_set1_pd(r.p2_1), p2_2 = _mm512_set1_pd(r.p2_2);
  const __m512d ex_0 = _mm512_set1_pd(r.ex_0), ex_1 = _mm512_set1_pd(r.ex_1);
  const __m512d ey_0 = _mm512_set1_pd(r.ey_0), ey_1 = _mm512_set1_pd(r.ey_1);
  const __m512d two_c = _mm512_set1_pd(r.two_c), beta = _mm512_set1_pd(r.beta);
  const __m512d csx = _mm512_set1_pd(r.csx), csy = _mm512_set1_pd(r.csy), ctx = _mm512_set1_pd(r.ctx);
  const __m512i fold_bit = r.fold_bit ? sign : izero, side_bit = r.side_bit ? sign : izero;
  const __m512d eight = _mm512_set1_pd(8.0);
  // t.x = x + 0.5 stepped by 8: integers plus a half, exact.
  __m512d tx = _mm512_add_pd(_mm512_set1_pd(x0 + 0.5), _mm512_setr_pd(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0));
  const int whole = n / 8 * 8;
  for (int i = 0; i < whole; i += 8, tx = _mm512_add_pd(tx, eight)) {
    const __m512d dx = _mm512_sub_pd(tx, ctx);
    const __m512d p1 = _mm512_add_pd(p1_0, _mm512_mul_pd(p1_1, dx));
    const __m512d al = _mm512_add_pd(al_0, _mm512_mul_pd(al_1, dx));
    const __m512d p2 = _mm512_add_pd(p2_0, _mm512_mul_pd(dx, _mm512_add_pd(p2_1, _mm512_mul_pd(dx, p2_2))));
    const __m512d disc = _mm512_add_pd(_mm512_mul_pd(p1, p1), _mm512_mul_pd(_mm512_mul_pd(two_c, two), p2));
    const __m512d root = _mm512_sqrt_pd(_mm512_max_pd(disc, zero));
    const __m512i p1_bits = _mm512_castpd_si512(p1);
    const __m512d signed_root =
        _mm512_castsi512_pd(_mm512_or_si512(_mm512_castpd_si512(root), _mm512_and_si512(sign, p1_bits)));
    const __m512d mu = _mm512_div_pd(two_c, _mm512_add_pd(p1, signed_root));
    const __m512i n_bits = _mm512_castpd_si512(_mm512_add_pd(_mm512_mul_pd(mu, al), beta));
    const __m512i mu_bits = _mm512_castpd_si512(mu);
    const __mmask8 no_root = negative(_mm512_castpd_si512(disc));
    const __mmask8 bad =
        no_root | negative(_mm512_xor_si512(_mm512_xor_si512(p1_bits, n_bits), fold_bit)) |
        negative(_mm512_xor_si512(_mm512_xor_si512(mu_bits, n_bits), side_bit)) |
        _mm512_cmp_pd_mask(_mm512_castsi512_pd(_mm512_andnot_si512(sign, mu_bits)), max_mu, _CMP_NLT_UQ);
    if (bad & ~no_root) {
      spanScalar(r, x0, i, i + 8, sx, sy, valid);
      continue;
    }
    const __m512d u = _mm512_add_pd(csx, _mm512_mul_pd(mu, _mm512_add_pd(ex_0, _mm512_mul_pd(ex_1, dx))));
    const __m512d v = _mm512_add_pd(csy, _mm512_mul_pd(mu, _mm512_add_pd(ey_0, _mm512_mul_pd(ey_1, dx))));
    storeEight(u, v, bad, sx + i, sy + i, valid + i);
  }
  spanScalar(r, x0, whole, n, sx, sy, valid);
}
#pragma GCC diagnostic pop
#endif

}  // namespace

bool CentralInverse::solve(const Eigen::Vector2d& t, Eigen::Vector2d& s) const {
  if (parallel_) return solveParallel(t, s);
  double u = 0.0, v = 0.0;
  if (!solvePixel(rowPolys(rows_, t.y()), t.x(), u, v)) return false;
  s = Eigen::Vector2d(u, v);
  return true;
}

void CentralInverse::span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid, int simd) const {
  if (parallel_) return spanParallel(y, x0, n, sx, sy, valid, simd);
  const RowPolys r = rowPolys(rows_, y + 0.5);
#if defined(__x86_64__)
  if (simd >= 2 && cpuHasAvx512f()) return spanAvx512(r, x0, n, sx, sy, valid);
  if (simd >= 1 && cpuHasAvx2()) return spanAvx2(r, x0, n, sx, sy, valid);
#endif
  spanScalar(r, x0, 0, n, sx, sy, valid);
}

}  // namespace artcam
