// SPDX-License-Identifier: Apache-2.0
// The parallel form of the central inverse (central_inverse.h): the target centre at infinity.
#include "core/model/structure.h"
#include "core/mapping/central_inverse.h"
#include "core/mapping/central_lanes.h"
#include "core/util/cpu_features.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace artcam {
namespace {

// As central_inverse.cpp's: factors below this (the forms scaled to 1) count as zero, and the
// factorisation must reproduce the map to this share of its frame.
constexpr double kRelativeTolerance = 1e-9;

// Positions beyond this many source pixels are no preimage: they would overflow float or
// sample nothing (the finite form's bound on μ, here on the position itself).
constexpr double kMaxPosition = 1e15;

// The upper triangle of a symmetric 3×3 matrix as 6 numbers.
Eigen::Matrix<double, 6, 1> upper(const Eigen::Matrix3d& m) {
  Eigen::Matrix<double, 6, 1> v;
  int row = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) v(row++) = m(i, j);
  return v;
}

// sym(l kᵀ) = (l kᵀ + k lᵀ) / 2 as a 6×3 matrix acting on k.
Eigen::Matrix<double, 6, 3> symWith(const Eigen::Vector3d& l) {
  Eigen::Matrix<double, 6, 3> a = Eigen::Matrix<double, 6, 3>::Zero();
  int row = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j, ++row) {
      a(row, j) += 0.5 * l(i);
      a(row, i) += 0.5 * l(j);
    }
  return a;
}

// A row's quantities as polynomials in dx = t.x − reference.x (evaluated per pixel, nothing
// accumulates): E(μ) = A μ² + B μ + C, s̃ (pixels) = S₀ + dx S₁ + μ S_c, l · s̃′ and g · s̃′.
struct ParallelRow {
  double a, four_a;           // A, 4A
  double b0, b1, b2;          // B = b0 + dx (b1 + dx b2)
  double c0, c1, c2, c3;      // C = c0 + dx (c1 + dx (c2 + dx c3))
  double sx0, sx1, sy0, sy1, sz0, sz1, scx, scy, scz;
  double l0, l1, lc, g0, g1;  // l · s̃′ = l0 + l1 dx + μ lc, g · s̃′ = g0 + g1 dx
  double refx;
  bool side_bit, fold_bit;
};

ParallelRow parallelRow(const CentralInverse::ParallelRows& w, double ty) {
  ParallelRow r{};
  const double dy = ty - w.reference.y();
  const double a0 = w.n.y() * dy / w.sigma, a1 = w.n.x() / w.sigma;
  const double b0 = w.d.y() * dy / w.sigma, b1 = w.d.x() / w.sigma;
  const Eigen::Vector3d p0 = w.p0 + a0 * w.p1, p1 = a1 * w.p1;  // p = p0 + dx p1
  const Eigen::Vector3d pc = w.along * w.cs;
  r.a = w.cs.dot(pc);
  r.four_a = 4.0 * r.a;
  const double beta0 = p0.dot(pc), beta1 = p1.dot(pc);
  r.lc = w.l.dot(w.cs);
  r.l0 = w.l.dot(p0), r.l1 = w.l.dot(p1);
  r.g0 = w.g.dot(p0), r.g1 = w.g.dot(p1);
  // B = 2 pᵀ P c̃_s − b (l · c̃_s)(g · p), C = pᵀ P p − b (l · p)(g · p); g · c̃_s = 0.
  r.b0 = 2.0 * beta0 - r.lc * b0 * r.g0;
  r.b1 = 2.0 * beta1 - r.lc * (b0 * r.g1 + b1 * r.g0);
  r.b2 = -r.lc * b1 * r.g1;
  const double pi0 = p0.dot(w.along * p0), pi1 = 2.0 * p0.dot(w.along * p1), pi2 = p1.dot(w.along * p1);
  const double rho0 = r.l0 * r.g0, rho1 = r.l0 * r.g1 + r.l1 * r.g0, rho2 = r.l1 * r.g1;
  r.c0 = pi0 - b0 * rho0;
  r.c1 = pi1 - (b0 * rho1 + b1 * rho0);
  r.c2 = pi2 - (b0 * rho2 + b1 * rho1);
  r.c3 = -b1 * rho2;
  const Eigen::Vector3d s0 = w.frame * p0, s1 = w.frame * p1, sc = w.frame * w.cs;
  r.sx0 = s0.x(), r.sx1 = s1.x(), r.sy0 = s0.y(), r.sy1 = s1.y(), r.sz0 = s0.z(), r.sz1 = s1.z();
  r.scx = sc.x(), r.scy = sc.y(), r.scz = sc.z();
  r.refx = w.reference.x();
  r.side_bit = w.den_negative;
  r.fold_bit = w.fold_bit;
  return r;
}

// The root μ's source point when it passes the rule: sb((l · s̃)(g · s̃)) is the centre's
// denominator's, sb(E′) ⊕ sb(s̃_z) is fold_bit (E′'s sign bit given as `e_neg`), and the
// position is finite and within kMaxPosition. The lanes below compute the same operations in
// the same order (this file is built without FP contraction): the same bits.
bool acceptRoot(const ParallelRow& r, double dx, double mu, bool e_neg, double& u, double& v) {
  const double ls = r.l0 + r.l1 * dx + mu * r.lc, gs = r.g0 + r.g1 * dx;
  const double sz = r.sz0 + r.sz1 * dx + mu * r.scz;
  if ((std::signbit(ls) != std::signbit(gs)) != r.side_bit) return false;
  if ((e_neg != std::signbit(sz)) != r.fold_bit) return false;
  const double inv = 1.0 / sz;
  u = (r.sx0 + r.sx1 * dx + mu * r.scx) * inv;
  v = (r.sy0 + r.sy1 * dx + mu * r.scy) * inv;
  return std::abs(u) < kMaxPosition && std::abs(v) < kMaxPosition;  // false for NaN
}

// Output point (tx, the row's ty): the stable root −2C / (B + sgn(B) √D), whose E′ has B's
// sign bit, and where it fails the rule the other, −(B + sgn(B) √D) / 2A, whose E′ has the
// opposite one (none when A = 0: E is linear, as the twist's is).
bool solvePixel(const ParallelRow& r, double tx, double& u, double& v) {
  const double dx = tx - r.refx;
  const double b = r.b0 + dx * (r.b1 + dx * r.b2);
  const double c = r.c0 + dx * (r.c1 + dx * (r.c2 + dx * r.c3));
  const double disc = b * b - r.four_a * c;
  if (std::signbit(disc) || std::isnan(disc)) return false;
  const double q = b + std::copysign(std::sqrt(disc), b);
  const bool b_neg = std::signbit(b);
  if (acceptRoot(r, dx, -2.0 * c / q, b_neg, u, v)) return true;
  return r.a != 0.0 && acceptRoot(r, dx, -0.5 * q / r.a, !b_neg, u, v);
}

// Pixels x0 + i, i0 ≤ i < n.
void spanScalar(const ParallelRow& r, int x0, int i0, int n, float* sx, float* sy, unsigned char* valid) {
  central_lanes::spanPixels(x0, i0, n, sx, sy, valid,
                            [&r](double tx, double& u, double& v) { return solvePixel(r, tx, u, v); });
}

#if defined(__x86_64__)
using central_lanes::negative;
using central_lanes::storeEight;
using central_lanes::storeFour;

// solvePixel's stable root in four lanes. A lane without a root (D < 0) or whose root fails
// is written empty when A = 0; otherwise a group with such a lane where D ≥ 0 (the other root
// may be its preimage) is redone by solvePixel.
__attribute__((target("avx2"))) void spanAvx2(const ParallelRow& r, int x0, int n, float* sx, float* sy,
                                              unsigned char* valid) {
  const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0), one = _mm256_set1_pd(1.0);
  const __m256d minus_two = _mm256_set1_pd(-2.0), max_pos = _mm256_set1_pd(kMaxPosition);
  const __m256d refx = _mm256_set1_pd(r.refx), four_a = _mm256_set1_pd(r.four_a);
  const __m256d b0 = _mm256_set1_pd(r.b0), b1 = _mm256_set1_pd(r.b1), b2 = _mm256_set1_pd(r.b2);
  const __m256d c0 = _mm256_set1_pd(r.c0), c1 = _mm256_set1_pd(r.c1), c2 = _mm256_set1_pd(r.c2),
                c3 = _mm256_set1_pd(r.c3);
  const __m256d l0 = _mm256_set1_pd(r.l0), l1 = _mm256_set1_pd(r.l1), lc = _mm256_set1_pd(r.lc);
  const __m256d g0 = _mm256_set1_pd(r.g0), g1 = _mm256_set1_pd(r.g1);
  const __m256d sx0 = _mm256_set1_pd(r.sx0), sx1 = _mm256_set1_pd(r.sx1), scx = _mm256_set1_pd(r.scx);
  const __m256d sy0 = _mm256_set1_pd(r.sy0), sy1 = _mm256_set1_pd(r.sy1), scy = _mm256_set1_pd(r.scy);
  const __m256d sz0 = _mm256_set1_pd(r.sz0), sz1 = _mm256_set1_pd(r.sz1), scz = _mm256_set1_pd(r.scz);
  const __m256d side_bit = r.side_bit ? sign : zero, fold_bit = r.fold_bit ? sign : zero;
  const bool other_root = r.a != 0.0;
  const __m256d lanes = _mm256_setr_pd(0.0, 1.0, 2.0, 3.0);
  const int whole = n / 4 * 4;
  for (int i = 0; i < whole; i += 4) {
    const __m256d dx = _mm256_sub_pd(_mm256_add_pd(_mm256_set1_pd(x0 + i + 0.5), lanes), refx);
    const __m256d b = _mm256_add_pd(b0, _mm256_mul_pd(dx, _mm256_add_pd(b1, _mm256_mul_pd(dx, b2))));
    const __m256d c = _mm256_add_pd(
        c0, _mm256_mul_pd(dx, _mm256_add_pd(c1, _mm256_mul_pd(dx, _mm256_add_pd(c2, _mm256_mul_pd(dx, c3))))));
    const __m256d disc = _mm256_sub_pd(_mm256_mul_pd(b, b), _mm256_mul_pd(four_a, c));
    const __m256d no_root = _mm256_or_pd(disc, _mm256_cmp_pd(disc, disc, _CMP_UNORD_Q));
    const __m256d root = _mm256_sqrt_pd(_mm256_max_pd(disc, zero));
    const __m256d q = _mm256_add_pd(b, _mm256_or_pd(root, _mm256_and_pd(sign, b)));
    const __m256d mu = _mm256_div_pd(_mm256_mul_pd(minus_two, c), q);
    const __m256d ls = _mm256_add_pd(_mm256_add_pd(l0, _mm256_mul_pd(l1, dx)), _mm256_mul_pd(mu, lc));
    const __m256d gs = _mm256_add_pd(g0, _mm256_mul_pd(g1, dx));
    const __m256d sz = _mm256_add_pd(_mm256_add_pd(sz0, _mm256_mul_pd(sz1, dx)), _mm256_mul_pd(mu, scz));
    const __m256d inv = _mm256_div_pd(one, sz);
    const __m256d u = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(sx0, _mm256_mul_pd(sx1, dx)), _mm256_mul_pd(mu, scx)), inv);
    const __m256d v = _mm256_mul_pd(
        _mm256_add_pd(_mm256_add_pd(sy0, _mm256_mul_pd(sy1, dx)), _mm256_mul_pd(mu, scy)), inv);
    // Sign bit set where a test fails.
    const __m256d far = _mm256_or_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, u), max_pos, _CMP_NLT_UQ),
                                     _mm256_cmp_pd(_mm256_andnot_pd(sign, v), max_pos, _CMP_NLT_UQ));
    const __m256d bad = _mm256_or_pd(
        _mm256_or_pd(no_root, far),
        _mm256_or_pd(_mm256_xor_pd(_mm256_xor_pd(ls, gs), side_bit), _mm256_xor_pd(_mm256_xor_pd(b, sz), fold_bit)));
    const int bad_bits = _mm256_movemask_pd(bad);
    if (other_root && (bad_bits & ~_mm256_movemask_pd(no_root))) {
      spanScalar(r, x0, i, i + 4, sx, sy, valid);
      continue;
    }
    // No root (D < 0): position 0, as the scalar code writes.
    storeFour(u, v, bad, sx + i, sy + i, valid + i);
  }
  spanScalar(r, x0, whole, n, sx, sy, valid);
}

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// spanAvx2 in eight lanes.
__attribute__((target("avx512f"))) void spanAvx512(const ParallelRow& r, int x0, int n, float* sx, float* sy,
                                                   unsigned char* valid) {
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0), minus_two = _mm512_set1_pd(-2.0);
  const __m512i sign = _mm512_set1_epi64(std::int64_t{1} << 63), izero = _mm512_setzero_si512();
  const __m512d max_pos = _mm512_set1_pd(kMaxPosition);
  const __m512d refx = _mm512_set1_pd(r.refx), four_a = _mm512_set1_pd(r.four_a);
  const __m512d b0 = _mm512_set1_pd(r.b0), b1 = _mm512_set1_pd(r.b1), b2 = _mm512_set1_pd(r.b2);
  const __m512d c0 = _mm512_set1_pd(r.c0), c1 = _mm512_set1_pd(r.c1), c2 = _mm512_set1_pd(r.c2),
                c3 = _mm512_set1_pd(r.c3);
  const __m512d l0 = _mm512_set1_pd(r.l0), l1 = _mm512_set1_pd(r.l1), lc = _mm512_set1_pd(r.lc);
  const __m512d g0 = _mm512_set1_pd(r.g0), g1 = _mm512_set1_pd(r.g1);
  const __m512d sx0 = _mm512_set1_pd(r.sx0), sx1 = _mm512_set1_pd(r.sx1), scx = _mm512_set1_pd(r.scx);
  const __m512d sy0 = _mm512_set1_pd(r.sy0), sy1 = _mm512_set1_pd(r.sy1), scy = _mm512_set1_pd(r.scy);
  const __m512d sz0 = _mm512_set1_pd(r.sz0), sz1 = _mm512_set1_pd(r.sz1), scz = _mm512_set1_pd(r.scz);
  const __m512i side_bit = r.side_bit ? sign : izero, fold_bit = r.fold_bit ? sign : izero;
  const bool other_root = r.a != 0.0;
  const __m512d eight = _mm512_set1_pd(8.0);
  // t.x = x + 0.5 stepped by 8: integers plus a half, exact.
  __m512d tx = _mm512_add_pd(_mm512_set1_pd(x0 + 0.5), _mm512_setr_pd(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0));
  const int whole = n / 8 * 8;
  for (int i = 0; i < whole; i += 8, tx = _mm512_add_pd(tx, eight)) {
    const __m512d dx = _mm512_sub_pd(tx, refx);
    const __m512d b = _mm512_add_pd(b0, _mm512_mul_pd(dx, _mm512_add_pd(b1, _mm512_mul_pd(dx, b2))));
    const __m512d c = _mm512_add_pd(
        c0, _mm512_mul_pd(dx, _mm512_add_pd(c1, _mm512_mul_pd(dx, _mm512_add_pd(c2, _mm512_mul_pd(dx, c3))))));
    const __m512d disc = _mm512_sub_pd(_mm512_mul_pd(b, b), _mm512_mul_pd(four_a, c));
    const __mmask8 no_root = negative(_mm512_castpd_si512(disc)) | _mm512_cmp_pd_mask(disc, disc, _CMP_UNORD_Q);
    const __m512d root = _mm512_sqrt_pd(_mm512_max_pd(disc, zero));
    const __m512i b_bits = _mm512_castpd_si512(b);
    const __m512d q = _mm512_add_pd(
        b, _mm512_castsi512_pd(_mm512_or_si512(_mm512_castpd_si512(root), _mm512_and_si512(sign, b_bits))));
    const __m512d mu = _mm512_div_pd(_mm512_mul_pd(minus_two, c), q);
    const __m512d ls = _mm512_add_pd(_mm512_add_pd(l0, _mm512_mul_pd(l1, dx)), _mm512_mul_pd(mu, lc));
    const __m512d gs = _mm512_add_pd(g0, _mm512_mul_pd(g1, dx));
    const __m512d sz = _mm512_add_pd(_mm512_add_pd(sz0, _mm512_mul_pd(sz1, dx)), _mm512_mul_pd(mu, scz));
    const __m512d inv = _mm512_div_pd(one, sz);
    const __m512d u = _mm512_mul_pd(
        _mm512_add_pd(_mm512_add_pd(sx0, _mm512_mul_pd(sx1, dx)), _mm512_mul_pd(mu, scx)), inv);
    const __m512d v = _mm512_mul_pd(
        _mm512_add_pd(_mm512_add_pd(sy0, _mm512_mul_pd(sy1, dx)), _mm512_mul_pd(mu, scy)), inv);
    const __mmask8 far =
        _mm512_cmp_pd_mask(_mm512_castsi512_pd(_mm512_andnot_si512(sign, _mm512_castpd_si512(u))), max_pos,
                           _CMP_NLT_UQ) |
        _mm512_cmp_pd_mask(_mm512_castsi512_pd(_mm512_andnot_si512(sign, _mm512_castpd_si512(v))), max_pos,
                           _CMP_NLT_UQ);
    const __m512i ls_gs = _mm512_xor_si512(_mm512_castpd_si512(ls), _mm512_castpd_si512(gs));
    const __mmask8 bad = no_root | far | negative(_mm512_xor_si512(ls_gs, side_bit)) |
                         negative(_mm512_xor_si512(_mm512_xor_si512(b_bits, _mm512_castpd_si512(sz)), fold_bit));
    if (other_root && (bad & ~no_root)) {
      spanScalar(r, x0, i, i + 8, sx, sy, valid);
      continue;
    }
    storeEight(u, v, bad, sx + i, sy + i, valid + i);
  }
  spanScalar(r, x0, whole, n, sx, sy, valid);
}
#pragma GCC diagnostic pop
#endif

}  // namespace

std::optional<CentralInverse> CentralInverse::detectParallel(const RationalMap& forward, FrameSize source_px,
                                                             const CentreReference& centre,
                                                             const std::array<Eigen::Matrix3d, 3>& u,
                                                             const Eigen::Matrix3d& frame, double sigma) {
  for (const Eigen::VectorXd& line : realLineFactors(u[2], kRelativeTolerance)) {
    const Eigen::Vector3d l = line;
    // The denominator's other line: u₂ = sym(l gᵀ).
    const Eigen::Matrix<double, 6, 3> sym_l = symWith(l);
    const Eigen::Vector3d g = sym_l.colPivHouseholderQr().solve(upper(u[2]));
    if ((sym_l * g - upper(u[2])).cwiseAbs().maxCoeff() > kRelativeTolerance) continue;
    // n₀ u₀ + n₁ u₁ = sym(l kᵀ): the null vector of [u₀ u₁ −sym(l ·)].
    Eigen::MatrixXd m(6, 5);  // dynamic: GCC 12 misreads the fixed-size SVD's storage
    m.col(0) = upper(u[0]);
    m.col(1) = upper(u[1]);
    m.rightCols<3>() = -sym_l;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullV);
    if (svd.singularValues()(4) > kRelativeTolerance) continue;
    Eigen::VectorXd x = svd.matrixV().col(4);
    const double n_norm = x.head(2).norm();
    if (!(n_norm > 1e-3)) continue;  // only the numerators' common factor: no direction
    x /= n_norm;
    ParallelRows w;
    w.n = x.head(2);
    w.d = Eigen::Vector2d(-w.n.y(), w.n.x());
    const Eigen::Vector3d k = x.tail(3);
    w.cs = k.cross(g);
    if (!(w.cs.norm() > kRelativeTolerance * k.norm() * g.norm())) continue;  // a constant coordinate
    w.cs.normalize();
    // p(a) on the line k − a g, on the fixed line c̃_s (which c̃_s is not on: c̃_s · c̃_s = 1).
    w.p0 = k.cross(w.cs);
    w.p1 = -g.cross(w.cs);
    w.along = w.d.x() * u[0] + w.d.y() * u[1];
    w.l = l;
    w.g = g;
    w.reference = centre.target;
    w.sigma = sigma;
    w.frame = frame;
    w.den_negative = (centre.denominator_signs & 1u) != 0;
    Eigen::Matrix3d basis;
    basis << w.p0, w.p1, w.cs;
    const double k_det = basis.determinant();
    if (!(std::abs(k_det) > kRelativeTolerance)) continue;
    // sb(det J) = sb(E′) ⊕ sb(den) ⊕ sb(det[p₀, p₁, c̃_s]) ⊕ sb(s̃_z) (det[n; d] = 1), with
    // sb(den) the centre's at a solution.
    w.fold_bit = (!centre.det_positive) != (w.den_negative != std::signbit(k_det));
    CentralInverse out;
    out.parallel_ = true;
    out.parallel_rows_ = w;
    // The factorisation must be the map, and its roots preimages: at a grid over the source
    // frame, F = reference + σ (a n + b d), and each output solves back to a point that maps
    // onto it.
    const Eigen::Matrix3d frame_inv = frame.inverse();
    Eigen::Vector2d centre_back;
    bool same = out.solveParallel(centre.target, centre_back) &&
                (centre_back - centre.source).norm() <= kRelativeTolerance * sigma;
    constexpr int kGrid = 9;
    for (int j = 0; j < kGrid && same; ++j)
      for (int i = 0; i < kGrid && same; ++i) {
        const Eigen::Vector2d s(source_px.width * i / (kGrid - 1.0), source_px.height * j / (kGrid - 1.0));
        Eigen::Vector2d f;
        if (!forward.evaluate(s, f, nullptr)) continue;
        const Eigen::Vector3d sh = frame_inv * Eigen::Vector3d(s.x(), s.y(), 1.0);
        const double a = k.dot(sh) / g.dot(sh), b = sh.dot(w.along * sh) / (l.dot(sh) * g.dot(sh));
        const Eigen::Vector2d model = w.reference + sigma * (a * w.n + b * w.d);
        const double scale = sigma + (f - w.reference).norm();
        same = (f - model).norm() <= kRelativeTolerance * scale;
        Eigen::Vector2d back, f_back;
        if (same && out.solveParallel(f, back))
          same = forward.evaluate(back, f_back, nullptr) && (f_back - f).norm() <= kRelativeTolerance * scale;
      }
    if (same) return out;
  }
  return std::nullopt;
}

bool CentralInverse::solveParallel(const Eigen::Vector2d& t, Eigen::Vector2d& s) const {
  double u = 0.0, v = 0.0;
  if (!solvePixel(parallelRow(parallel_rows_, t.y()), t.x(), u, v)) return false;
  s = Eigen::Vector2d(u, v);
  return true;
}

void CentralInverse::spanParallel(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
                                  int simd) const {
  const ParallelRow r = parallelRow(parallel_rows_, y + 0.5);
#if defined(__x86_64__)
  if (simd >= 2 && cpuHasAvx512f()) return spanAvx512(r, x0, n, sx, sy, valid);
  if (simd >= 1 && cpuHasAvx2()) return spanAvx2(r, x0, n, sx, sy, valid);
#endif
  spanScalar(r, x0, 0, n, sx, sy, valid);
}

}  // namespace artcam
