// SPDX-License-Identifier: Apache-2.0
#include "core/render/coordinates.h"

#include "core/model/frames.h"
#include "core/render/inverse_seed.h"
#include "core/util/parallel.h"

#include <Eigen/LU>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

// One span of the inverse homography, all kSpanPixels lanes and no branches so it vectorises
// (the AVX2 clone runs four doubles at once): s = (h0 + i · column) / w, i · step rather than
// a running sum so nothing drifts. `sign` is +1 when the centre's w is positive.
struct ProjectiveRow {
  double x, y, w, dx, dy, dw, sign;
};

[[gnu::always_inline]] inline void projectiveSpanBody(const ProjectiveRow& r, float* __restrict sx,
                                                      float* __restrict sy,
                                                      std::int32_t* __restrict ok) {
  for (int i = 0; i < kSpanPixels; ++i) {
    const double t = i;
    const double w = r.w + t * r.dw;
    const double inv = 1.0 / w;
    const double u = (r.x + t * r.dx) * inv, v = (r.y + t * r.dy) * inv;
    // Beyond the horizon, or so close to it that the point overflows float: no preimage.
    const bool good = (w * r.sign > 0.0) & (std::abs(u) < 1e30) & (std::abs(v) < 1e30);
    sx[i] = good ? static_cast<float>(u) : 0.0f;
    sy[i] = good ? static_cast<float>(v) : 0.0f;
    ok[i] = good;
  }
}

#if defined(__x86_64__)
// GCC's -O2 does not vectorise the loop above (its cheap cost model), so the AVX2 version is
// written out: the same operations in the same order, no FMA, hence bit-identical results.
__attribute__((target("avx2"))) void projectiveSpanAvx2(const ProjectiveRow& r, float* sx, float* sy,
                                                        std::int32_t* ok) {
  const __m256d x = _mm256_set1_pd(r.x), y = _mm256_set1_pd(r.y), w0 = _mm256_set1_pd(r.w);
  const __m256d dx = _mm256_set1_pd(r.dx), dy = _mm256_set1_pd(r.dy), dw = _mm256_set1_pd(r.dw);
  const __m256d sign = _mm256_set1_pd(r.sign), one = _mm256_set1_pd(1.0), big = _mm256_set1_pd(1e30);
  const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll));
  const __m256d four = _mm256_set1_pd(4.0);
  __m256d t = _mm256_setr_pd(0.0, 1.0, 2.0, 3.0);
  for (int i = 0; i < kSpanPixels; i += 4, t = _mm256_add_pd(t, four)) {
    const __m256d w = _mm256_add_pd(w0, _mm256_mul_pd(t, dw));
    const __m256d inv = _mm256_div_pd(one, w);
    const __m256d u = _mm256_mul_pd(_mm256_add_pd(x, _mm256_mul_pd(t, dx)), inv);
    const __m256d v = _mm256_mul_pd(_mm256_add_pd(y, _mm256_mul_pd(t, dy)), inv);
    const __m256d good = _mm256_and_pd(
        _mm256_cmp_pd(_mm256_mul_pd(w, sign), _mm256_setzero_pd(), _CMP_GT_OQ),
        _mm256_and_pd(_mm256_cmp_pd(_mm256_and_pd(u, abs_mask), big, _CMP_LT_OQ),
                      _mm256_cmp_pd(_mm256_and_pd(v, abs_mask), big, _CMP_LT_OQ)));
    _mm_storeu_ps(sx + i, _mm256_cvtpd_ps(_mm256_and_pd(u, good)));
    _mm_storeu_ps(sy + i, _mm256_cvtpd_ps(_mm256_and_pd(v, good)));
    const int bits = _mm256_movemask_pd(good);
    for (int k = 0; k < 4; ++k) ok[i + k] = (bits >> k) & 1;
  }
}


// A span of the inverse homography in float, eight lanes, re-anchored at the span's first
// pixel: with (X, Y, W) + t (dX, dY, dW) the homogeneous source point and s₀ = (X, Y) / W,
//   s(t) = s₀ + t β / (1 + γ t),  β = (dX, dY) − s₀ dW) / W, γ = dW / W,
// exactly; only the offset from s₀ is float (~64 px · 2⁻²⁴), the division _mm256_rcp_ps and one
// Newton step. Only for spans without a horizon (ProjectiveKernel::span checks).
// Float spans only where positions stay within this (source pixels): half an ulp ≤ 1e-3 px.
constexpr double kFloatSpanLimit = 16384.0;

struct ProjectiveSpanF {
  float base_x, base_y, beta_x, beta_y, gamma;
};

// kAffine: γ = 0, no division (rcp + Newton of 1 is 1 − ~2⁻²⁴, which an identity would show).
template <bool kAffine>
__attribute__((target("avx2"))) void projectiveSpanFloatAvx2(const ProjectiveSpanF& f, float* sx, float* sy) {
  const __m256 bx = _mm256_set1_ps(f.base_x), by = _mm256_set1_ps(f.base_y);
  const __m256 betax = _mm256_set1_ps(f.beta_x), betay = _mm256_set1_ps(f.beta_y);
  const __m256 gamma = _mm256_set1_ps(f.gamma);
  const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f), eight = _mm256_set1_ps(8.0f);
  __m256 t = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  for (int i = 0; i < kSpanPixels; i += 8, t = _mm256_add_ps(t, eight)) {
    __m256 tr = t;
    if constexpr (!kAffine) {
      const __m256 d = _mm256_add_ps(one, _mm256_mul_ps(t, gamma));
      const __m256 r0 = _mm256_rcp_ps(d);
      tr = _mm256_mul_ps(t, _mm256_mul_ps(r0, _mm256_sub_ps(two, _mm256_mul_ps(d, r0))));
    }
    _mm256_storeu_ps(sx + i, _mm256_add_ps(bx, _mm256_mul_ps(tr, betax)));
    _mm256_storeu_ps(sy + i, _mm256_add_ps(by, _mm256_mul_ps(tr, betay)));
  }
}

#endif

bool cpuHasAvx2() {
#if defined(__x86_64__)
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

void projectiveSpanDispatched(const ProjectiveRow& r, float* sx, float* sy, std::int32_t* ok) {
#if defined(__x86_64__)
  if (cpuHasAvx2()) return projectiveSpanAvx2(r, sx, sy, ok);
#endif
  projectiveSpanBody(r, sx, sy, ok);
}

void projectiveSpanScalar(const ProjectiveRow& r, float* sx, float* sy, std::int32_t* ok) {
  projectiveSpanBody(r, sx, sy, ok);
}

class ProjectiveKernel final : public CoordinateKernel {
 public:
  ProjectiveKernel(const Eigen::Matrix3d& target_from_source, FrameSize source_px, bool scalar_only)
      : scalar_only_(scalar_only) {
    const Eigen::Matrix3d& h = target_from_source;
    // An affine map keeps w constant; invert it in closed form so the last row stays exactly
    // (0, 0, 1) and the span loop can skip the division.
    affine_ = h(2, 0) == 0.0 && h(2, 1) == 0.0 && h(2, 2) != 0.0;
    if (affine_) {
      const Eigen::Matrix2d a = h.topLeftCorner<2, 2>() / h(2, 2);
      const Eigen::Vector2d b = h.topRightCorner<2, 1>() / h(2, 2);
      const Eigen::FullPivLU<Eigen::Matrix2d> lu(a);
      if (!lu.isInvertible()) throw std::invalid_argument("the camera's affine map is singular");
      m_.setZero();
      m_.topLeftCorner<2, 2>() = lu.inverse();
      m_.topRightCorner<2, 1>() = -m_.topLeftCorner<2, 2>() * b;
      m_(2, 2) = 1.0;
      centre_positive_ = true;
    } else {
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(h);
      if (!lu.isInvertible()) throw std::invalid_argument("the camera's homography is singular");
      m_ = lu.inverse();
      const double scale = m_.cwiseAbs().maxCoeff();
      if (!(scale > 0.0) || !m_.allFinite())
        throw std::invalid_argument("the camera's homography has no finite inverse");
      m_ /= scale;  // a positive factor keeps every sign below
      // The forward denominator at s_h / s_h3 is 1 / s_h3 up to a positive scale (inverse.cpp).
      const Eigen::Vector3d centre(source_px.width / 2.0, source_px.height / 2.0, 1.0);
      centre_positive_ = (h * centre).z() > 0.0;
    }
    if (!m_.allFinite()) throw std::invalid_argument("the camera's homography has no finite inverse");
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState&) const override {
    const Eigen::Vector3d h0 = m_ * Eigen::Vector3d(x0 + 0.5, y + 0.5, 1.0);
    const double dx = m_(0, 0), dy = m_(1, 0), dw = m_(2, 0);
    const ProjectiveRow r{h0.x(), h0.y(), h0.z(), dx, dy, dw, centre_positive_ ? 1.0 : -1.0};
#if defined(__x86_64__)
    // Affine maps too (W = 1, γ = 0): the float lanes beat the double loop below.
    if (!scalar_only_ && cpuHasAvx2()) {
      // W is linear along the span: on the centre's side at both ends means on it throughout,
      // and then each coordinate is monotone, so its ends bound it. Float only where it is
      // exact enough: W changing by at most 2× over the span (1 + γ t computed without
      // cancellation) and positions within ±kFloatSpanLimit (half an ulp ≤ 1e-3 px).
      const double w_end = r.w + (n - 1) * r.dw;
      const double u0 = r.x / r.w, v0 = r.y / r.w;
      const double u1 = (r.x + (n - 1) * r.dx) / w_end, v1 = (r.y + (n - 1) * r.dy) / w_end;
      const double ratio = w_end / r.w;
      if (r.w * r.sign > 0.0 && ratio >= 0.5 && ratio <= 2.0 &&
          std::max({std::abs(u0), std::abs(v0), std::abs(u1), std::abs(v1)}) <= kFloatSpanLimit) {
        const ProjectiveSpanF f{static_cast<float>(u0), static_cast<float>(v0),
                                static_cast<float>((r.dx - u0 * r.dw) / r.w),
                                static_cast<float>((r.dy - v0 * r.dw) / r.w), static_cast<float>(r.dw / r.w)};
        // All kSpanPixels lanes: sx, sy have the room.
        (r.dw == 0.0 ? projectiveSpanFloatAvx2<true> : projectiveSpanFloatAvx2<false>)(f, sx, sy);
        std::fill(valid, valid + n, static_cast<unsigned char>(1));
        return 0;
      }
    }
#endif
    if (affine_) {
      for (int i = 0; i < n; ++i) {
        sx[i] = static_cast<float>(h0.x() + i * dx);
        sy[i] = static_cast<float>(h0.y() + i * dy);
        valid[i] = 1;
      }
      return 0;
    }
    float fx[kSpanPixels], fy[kSpanPixels];
    std::int32_t ok[kSpanPixels];
    (scalar_only_ ? projectiveSpanScalar : projectiveSpanDispatched)(r, fx, fy, ok);
    for (int i = 0; i < n; ++i) {
      sx[i] = fx[i];
      sy[i] = fy[i];
      valid[i] = static_cast<unsigned char>(ok[i] != 0);
    }
    return 0;
  }

  bool sourceJacobian(const Eigen::Vector2d& t, const Eigen::Vector2d& s,
                      Eigen::Matrix2d& j) const override {
    const double w = m_.row(2).dot(Eigen::Vector3d(t.x(), t.y(), 1.0));
    if (!(std::abs(w) > 0.0)) return false;
    // d(X/W) = (∇X − s ∇W) / W.
    j.row(0) = (m_.block<1, 2>(0, 0) - s.x() * m_.block<1, 2>(2, 0)) / w;
    j.row(1) = (m_.block<1, 2>(1, 0) - s.y() * m_.block<1, 2>(2, 0)) / w;
    return j.allFinite();
  }

  std::optional<std::array<int, 2>> wholePixelOffset() const override {
    if (!affine_) return std::nullopt;
    if (!(m_.topLeftCorner<2, 2>() - Eigen::Matrix2d::Identity()).isZero(1e-12)) return std::nullopt;
    const double tx = m_(0, 2), ty = m_(1, 2);
    if (std::abs(tx - std::round(tx)) > 1e-9 || std::abs(ty - std::round(ty)) > 1e-9) return std::nullopt;
    if (std::abs(tx) > 1e9 || std::abs(ty) > 1e9) return std::nullopt;
    return std::array<int, 2>{static_cast<int>(std::lround(tx)), static_cast<int>(std::lround(ty))};
  }

 private:
  bool scalar_only_ = false;
  Eigen::Matrix3d m_;  // source_from_target, column form, pixels
  bool affine_ = false;
  bool centre_positive_ = true;
};

// One quadratic form x Q xᵀ of x = (u, v, 1) as n = a u² + b uv + c u + d v² + e v + f.
struct Quadratic {
  double a, b, c, d, e, f;
  explicit Quadratic(const Eigen::Matrix3d& q)
      : a(q(0, 0)), b(2 * q(0, 1)), c(2 * q(0, 2)), d(q(1, 1)), e(2 * q(1, 2)), f(q(2, 2)) {}
  double value(double u, double v) const { return (a * u + b * v + c) * u + (d * v + e) * v + f; }
  double du(double u, double v) const { return 2 * a * u + b * v + c; }
  double dv(double u, double v) const { return b * u + 2 * d * v + e; }
};

// What the seed check needs of the one-stage forward map and of the centre (inverse.h).
struct CheckInputs {
  Quadratic f0, f1, f2;
  bool den_negative;  // the centre's denominator is negative
  bool det_positive;  // the centre's Jacobian determinant is positive
  double tolerance;
};

// The seed check (RationalKernel::check) for a whole span of starts in plain doubles without
// branches, so it vectorises: q = start − δ, passed = 1 where the check accepts. SIMD by
// runtime dispatch: GCC clones the function for AVX2 and the x86-64 baseline and
// picks one when the program loads (ifunc); no -march flag anywhere, and the baseline clone
// is the scalar fallback machines without AVX2 run; CoordinateOptions::scalar_only forces it
// so the tests compare the two (no FMA in either, so they agree bit for bit).
[[gnu::always_inline]] inline void checkSpanBody(
    const CheckInputs& in, double tx0, double ty, const double* __restrict bx,
    const double* __restrict by, double* __restrict qx, double* __restrict qy,
    std::int64_t* __restrict passed) {
  const Quadratic f0 = in.f0, f1 = in.f1, f2 = in.f2;
  for (int i = 0; i < kSpanPixels; ++i) {
    const double u = bx[i], v = by[i];
    const double den = f2.value(u, v), inv = 1.0 / den;
    const double fx = f0.value(u, v) * inv, fy = f1.value(u, v) * inv;
    const double du = f2.du(u, v), dv = f2.dv(u, v);
    const double j00 = (f0.du(u, v) - fx * du) * inv, j01 = (f0.dv(u, v) - fx * dv) * inv;
    const double j10 = (f1.du(u, v) - fy * du) * inv, j11 = (f1.dv(u, v) - fy * dv) * inv;
    const double det = j00 * j11 - j01 * j10, inv_det = 1.0 / det;
    const double rx = fx - (tx0 + i), ry = fy - ty;
    const double stepx = (j11 * rx - j01 * ry) * inv_det, stepy = (j00 * ry - j10 * rx) * inv_det;
    qx[i] = u - stepx;
    qy[i] = v - stepy;
    // The comparisons are false for NaN (a start on the pole, a singular Jacobian): rejected.
    // Comparisons combined with & rather than && so the loop body has no branch.
    const bool side = (den < 0.0) == in.den_negative;
    const bool fold = (det > 0.0) == in.det_positive;
    passed[i] = side & fold & (std::abs(stepx) <= in.tolerance) & (std::abs(stepy) <= in.tolerance);
  }
}

__attribute__((target_clones("avx2", "default"))) void checkSpanDispatched(
    const CheckInputs& in, double tx0, double ty, const double* bx, const double* by, double* qx,
    double* qy, std::int64_t* passed) {
  checkSpanBody(in, tx0, ty, bx, by, qx, qy, passed);
}

void checkSpanScalar(const CheckInputs& in, double tx0, double ty, const double* bx,
                     const double* by, double* qx, double* qy, std::int64_t* passed) {
  checkSpanBody(in, tx0, ty, bx, by, qx, qy, passed);
}

// A certified cell's pixels (RationalKernel::fastSpan): the seed by its closed-form quadratics
// along the row, n_k(i) = c_k + i (b_k + i a_k) at pixel x0 + i (eq 3), one division per pixel,
// plus the grid correction, linear along the cell: corr(i) = l + i · slope. kGridPixels lanes
// from pixel `first`, no branches, so it vectorises.
struct SeedRow {
  double a[3], b[3], c[3];
  double lx, ly, slope_x, slope_y;
};
constexpr int kGridPixels = kSpanPixels / 2;  // RationalKernel::kGrid

[[gnu::always_inline]] inline void seedCellBody(const SeedRow& r, int first, float* __restrict sx,
                                                float* __restrict sy) {
  for (int j = 0; j < kGridPixels; ++j) {
    const double t = first + j;
    const double n0 = r.c[0] + t * (r.b[0] + t * r.a[0]);
    const double n1 = r.c[1] + t * (r.b[1] + t * r.a[1]);
    const double n2 = r.c[2] + t * (r.b[2] + t * r.a[2]);
    const double inv = 1.0 / n2;
    sx[j] = static_cast<float>(n0 * inv + (r.lx + t * r.slope_x));
    sy[j] = static_cast<float>(n1 * inv + (r.ly + t * r.slope_y));
  }
}

#if defined(__x86_64__)
// A certified span (both cells) in float, eight lanes (float offsets relative to
// the span's origin). Re-anchored at the span's first pixel in double: with
// n_k(j) = c_k + j (b_k + j a_k) the seed's forms there (eq 3) and s₀ = (c_0, c_1) / c_2,
//   seed(j) = s₀ + j (β + j α) / (1 + j (γ + j δ)),  β = (b − s₀ b_2) / c_2, α = (a − s₀ a_2) / c_2,
// γ = b_2 / c_2, δ = a_2 / c_2, exactly; only the offset from s₀ (≤ 64 px plus the lens's
// stretch) is float, so its rounding is ~64 · 2⁻²⁴ px, and the one rounding of s₀ + offset to
// float is the half ulp every float position has anyway (≤ 2.4e-4 px at 6000 px). The
// division is _mm256_rcp_ps and one Newton step (relative error ~2⁻²², ~1e-5 px on the
// offset). The grid correction is linear along each cell: l_c + j k_c.
struct SeedSpanF {
  float base_x, base_y, beta_x, alpha_x, beta_y, alpha_y, gamma, delta;
  float lx[2], ly[2], kx[2], ky[2];  // per cell
};

// The seed's part of SeedSpanF from the forms at the span's first pixel; false where float
// would not be exact enough (as for homographies: the denominator changing by more than 2×
// over the span, or the seed beyond ±kFloatSpanLimit), and the caller takes the double code.
bool anchorSpan(const SeedRow& r, SeedSpanF& f) {
  const double inv = 1.0 / r.c[2];
  const double s0x = r.c[0] * inv, s0y = r.c[1] * inv;
  const double t = kSpanPixels - 1;
  const double ratio = (r.c[2] + t * (r.b[2] + t * r.a[2])) * inv;
  if (!(ratio >= 0.5 && ratio <= 2.0 && std::abs(s0x) <= kFloatSpanLimit && std::abs(s0y) <= kFloatSpanLimit))
    return false;
  f.base_x = static_cast<float>(s0x);
  f.base_y = static_cast<float>(s0y);
  f.beta_x = static_cast<float>((r.b[0] - s0x * r.b[2]) * inv);
  f.alpha_x = static_cast<float>((r.a[0] - s0x * r.a[2]) * inv);
  f.beta_y = static_cast<float>((r.b[1] - s0y * r.b[2]) * inv);
  f.alpha_y = static_cast<float>((r.a[1] - s0y * r.a[2]) * inv);
  f.gamma = static_cast<float>(r.b[2] * inv);
  f.delta = static_cast<float>(r.a[2] * inv);
  return true;
}

__attribute__((target("avx2"))) void seedSpanFloatAvx2(const SeedSpanF& f, float* sx, float* sy) {
  const __m256 bx = _mm256_set1_ps(f.base_x), by = _mm256_set1_ps(f.base_y);
  const __m256 betax = _mm256_set1_ps(f.beta_x), alphax = _mm256_set1_ps(f.alpha_x);
  const __m256 betay = _mm256_set1_ps(f.beta_y), alphay = _mm256_set1_ps(f.alpha_y);
  const __m256 gamma = _mm256_set1_ps(f.gamma), delta = _mm256_set1_ps(f.delta);
  const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f), eight = _mm256_set1_ps(8.0f);
  __m256 j = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  for (int cell = 0; cell < 2; ++cell) {
    const __m256 lx = _mm256_set1_ps(f.lx[cell]), ly = _mm256_set1_ps(f.ly[cell]);
    const __m256 kx = _mm256_set1_ps(f.kx[cell]), ky = _mm256_set1_ps(f.ky[cell]);
    for (int g = 0; g < kGridPixels; g += 8, j = _mm256_add_ps(j, eight)) {
      const int i = cell * kGridPixels + g;
      const __m256 d = _mm256_add_ps(one, _mm256_mul_ps(j, _mm256_add_ps(gamma, _mm256_mul_ps(j, delta))));
      const __m256 r0 = _mm256_rcp_ps(d);
      const __m256 r = _mm256_mul_ps(r0, _mm256_sub_ps(two, _mm256_mul_ps(d, r0)));
      const __m256 ox = _mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(betax, _mm256_mul_ps(j, alphax)), r), kx);
      const __m256 oy = _mm256_add_ps(_mm256_mul_ps(_mm256_add_ps(betay, _mm256_mul_ps(j, alphay)), r), ky);
      _mm256_storeu_ps(sx + i, _mm256_add_ps(_mm256_add_ps(bx, lx), _mm256_mul_ps(j, ox)));
      _mm256_storeu_ps(sy + i, _mm256_add_ps(_mm256_add_ps(by, ly), _mm256_mul_ps(j, oy)));
    }
  }
}

// The same span sixteen lanes at a time where the CPU has AVX-512F (runtime dispatch, as
// above): half the instructions of the AVX2 loop, which costs ~20 % of a certified render's
// CPU. The division is _mm512_rcp14_ps and one Newton step (relative error ~2⁻²⁸, below the
// AVX2 loop's), and the compiler may fuse products and sums, so the lanes differ from the
// AVX2 ones in the last bits only; the tests hold both to the same bounds (the scalar double
// code within 1e-3 px, the exact inverse within 1/256 px) through the dispatch.
#pragma GCC diagnostic push
// GCC 12's intrinsics start from _mm512_undefined_*() (a self-initialised variable): a false
// positive of both warnings.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
__attribute__((target("avx512f"))) void seedSpanFloatAvx512(const SeedSpanF& f, float* sx, float* sy) {
  const __m512 bx = _mm512_set1_ps(f.base_x), by = _mm512_set1_ps(f.base_y);
  const __m512 betax = _mm512_set1_ps(f.beta_x), alphax = _mm512_set1_ps(f.alpha_x);
  const __m512 betay = _mm512_set1_ps(f.beta_y), alphay = _mm512_set1_ps(f.alpha_y);
  const __m512 gamma = _mm512_set1_ps(f.gamma), delta = _mm512_set1_ps(f.delta);
  const __m512 one = _mm512_set1_ps(1.0f), two = _mm512_set1_ps(2.0f), sixteen = _mm512_set1_ps(16.0f);
  __m512 j = _mm512_setr_ps(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  for (int cell = 0; cell < 2; ++cell) {
    const __m512 lx = _mm512_set1_ps(f.lx[cell]), ly = _mm512_set1_ps(f.ly[cell]);
    const __m512 kx = _mm512_set1_ps(f.kx[cell]), ky = _mm512_set1_ps(f.ky[cell]);
    const __m512 base_x = _mm512_add_ps(bx, lx), base_y = _mm512_add_ps(by, ly);
    for (int g = 0; g < kGridPixels; g += 16, j = _mm512_add_ps(j, sixteen)) {
      const int i = cell * kGridPixels + g;
      const __m512 d = _mm512_add_ps(one, _mm512_mul_ps(j, _mm512_add_ps(gamma, _mm512_mul_ps(j, delta))));
      const __m512 r0 = _mm512_rcp14_ps(d);
      const __m512 r = _mm512_mul_ps(r0, _mm512_sub_ps(two, _mm512_mul_ps(d, r0)));
      const __m512 ox = _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(betax, _mm512_mul_ps(j, alphax)), r), kx);
      const __m512 oy = _mm512_add_ps(_mm512_mul_ps(_mm512_add_ps(betay, _mm512_mul_ps(j, alphay)), r), ky);
      _mm512_storeu_ps(sx + i, _mm512_add_ps(base_x, _mm512_mul_ps(j, ox)));
      _mm512_storeu_ps(sy + i, _mm512_add_ps(base_y, _mm512_mul_ps(j, oy)));
    }
  }
}
#pragma GCC diagnostic pop

bool cpuHasAvx512f() {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}

#endif

void seedCell(const SeedRow& r, int first, float* sx, float* sy) { seedCellBody(r, first, sx, sy); }

class RationalKernel final : public CoordinateKernel {
 public:
  RationalKernel(RationalMap forward, std::optional<RationalMap> seed, FrameSize source_px,
                 FrameSize target_px, const CoordinateOptions& options, int threads)
      : newton_(std::move(forward), source_px, options.residual_tolerance_px),
        seed_tolerance_(options.seed_tolerance_px),
        certify_tolerance_(options.certify_tolerance_px),
        scalar_only_(options.scalar_only),
        avx512_(options.allow_avx512) {
    if (seed && seed->stageCount() == 1) seed_q_ = seed->stage(0);
    for (const Eigen::Matrix3d& q : seed_q_) seed_forms_.emplace_back(q);
    if (newton_.forward().stageCount() == 1)
      for (const Eigen::Matrix3d& q : newton_.forward().stage(0)) forward_q_.emplace_back(q);
    buildCorrectionGrid(target_px, threads);
    certifyCells(threads);
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState& state) const override {
    const double ty = y + 0.5;
    // The grid correction: bilinear in y once per cell, then linear in x along the cell.
    const int gj = std::min(static_cast<int>(ty / kGrid), grid_h_ - 2);
    const double fy = ty / kGrid - gj;
    if (spanCertified(x0, n, gj)) return fastSpan(y, x0, n, gj, fy, sx, sy, valid, state);
    double corr_x[kSpanPixels], corr_y[kSpanPixels];
    for (int c0 = 0; c0 < n; c0 += kGrid) {
      const int gi = (x0 + c0) / kGrid, c1 = std::min(n, c0 + kGrid);
      Eigen::Vector2d left(0, 0), slope(0, 0);
      if (gi + 1 < grid_w_ && cellValid(gi, gj)) {
        left = (1 - fy) * node(gi, gj) + fy * node(gi, gj + 1);
        const Eigen::Vector2d right = (1 - fy) * node(gi + 1, gj) + fy * node(gi + 1, gj + 1);
        slope = (right - left) / kGrid;
        left -= slope * (gi * kGrid);  // so that correction(tx) = left + slope · tx
      }
      for (int i = c0; i < c1; ++i) {
        corr_x[i] = left.x() + slope.x() * (x0 + i + 0.5);
        corr_y[i] = left.y() + slope.y() * (x0 + i + 0.5);
      }
    }
    // Pass 1, every pixel independent (plain arrays the compiler may vectorise): the seed by
    // forward differences, the grid correction, and the one-evaluation check.
    double bx[kSpanPixels], by[kSpanPixels], qx[kSpanPixels], qy[kSpanPixels];
    unsigned char have[kSpanPixels], passed[kSpanPixels];
    if (!seed_q_.empty()) {
      // Forward differences (two adds a pixel) in locals the compiler keeps in registers.
      const RowQuadratics seed_row(seed_q_, y, x0);
      double n0 = seed_row.numerator(0), n1 = seed_row.numerator(1), n2 = seed_row.numerator(2);
      double d0 = seed_row.delta(0), d1 = seed_row.delta(1), d2 = seed_row.delta(2);
      const double s0 = seed_row.second(0), s1 = seed_row.second(1), s2 = seed_row.second(2);
      for (int i = 0; i < n; ++i) {
        bx[i] = n0 / n2;
        by[i] = n1 / n2;
        n0 += d0;
        n1 += d1;
        n2 += d2;
        d0 += s0;
        d1 += s1;
        d2 += s2;
      }
    } else {
      for (int i = 0; i < n; ++i) {
        bx[i] = x0 + i + 0.5;
        by[i] = ty;
      }
    }
    for (int i = 0; i < n; ++i) {
      bx[i] += corr_x[i];
      by[i] += corr_y[i];
      have[i] = std::isfinite(bx[i]) && std::isfinite(by[i]);
    }
    if (forward_q_.size() == 3) {
      for (int i = n; i < kSpanPixels; ++i) bx[i] = by[i] = 0.0;  // the kernel runs all lanes
      std::int64_t accepted[kSpanPixels];
      const CheckInputs in{forward_q_[0], forward_q_[1], forward_q_[2],
                           (newton_.centre().denominator_signs & 1u) != 0,
                           newton_.centre().det_positive, seed_tolerance_};
      (scalar_only_ ? checkSpanScalar : checkSpanDispatched)(in, x0 + 0.5, ty, bx, by, qx, qy, accepted);
      for (int i = 0; i < n; ++i) passed[i] = have[i] && accepted[i] != 0;
    } else {
      for (int i = 0; i < n; ++i) {
        Eigen::Vector2d q;
        passed[i] = have[i] && check(Eigen::Vector2d(x0 + i + 0.5, ty), Eigen::Vector2d(bx[i], by[i]), q);
        qx[i] = q.x();
        qy[i] = q.y();
      }
    }

    // Pass 2, in order along the row: the pixels the seed missed try the extrapolation of
    // their solved neighbours, then Newton. The row state is brought up to date only where a
    // pixel needs it and at the end (solutions live in qx, qy meanwhile).
    const RowState before = state;
    const auto solution = [&](int j) {
      if (j >= 0) return Eigen::Vector2d(qx[j], qy[j]);
      return j == -1 ? before.previous : j == -2 ? before.before_previous : before.third;
    };
    int run = before.run, last_base = -1, newton_count = 0;
    for (int i = 0; i < n; ++i) {
      if (passed[i]) {
        sx[i] = static_cast<float>(qx[i]);
        sy[i] = static_cast<float>(qy[i]);
        valid[i] = 1;
        last_base = i;
        ++run;
        continue;
      }
      const Eigen::Vector2d t(x0 + i + 0.5, ty);
      const Eigen::Vector2d base(bx[i], by[i]);
      const Eigen::Vector2d previous = solution(i - 1), before_previous = solution(i - 2);
      const Eigen::Vector2d seed_offset =
          last_base >= 0 ? Eigen::Vector2d(qx[last_base] - bx[last_base], qy[last_base] - by[last_base])
                         : before.seed_offset;
      Eigen::Vector2d s;
      bool ok = false, from_base = false;
      // Quadratic extrapolation of the last three solutions misses by the map's third
      // derivative (~1e-5 px); linear by its second, which strong lenses make ~1e-2 px.
      if (run >= 3) ok = check(t, 3.0 * (previous - before_previous) + solution(i - 3), s);
      if (!ok && run == 2) ok = check(t, 2.0 * previous - before_previous, s);
      if (!ok && have[i] && run >= 1) ok = from_base = check(t, base + seed_offset, s);
      if (!ok) {
        ++newton_count;
        if (run >= 2) ok = newton_.solve(t, 2.0 * previous - before_previous, s, kQuickIterations);
        if (!ok && have[i]) ok = from_base = newton_.solve(t, base, s, kQuickIterations);
        if (!ok && run >= 1) ok = newton_.solve(t, previous, s, kQuickIterations);
        if (!ok) ok = newton_.solveFromCentre(t, s, kMaxIterations);
      }
      valid[i] = ok ? 1 : 0;
      if (ok) {
        sx[i] = static_cast<float>(s.x());
        sy[i] = static_cast<float>(s.y());
        qx[i] = s.x();
        qy[i] = s.y();
        if (from_base) last_base = i;
        ++run;
      } else {
        sx[i] = sy[i] = 0.0f;
        run = 0;
      }
    }
    state.previous = solution(n - 1);
    state.before_previous = solution(n - 2);
    state.third = solution(n - 3);
    if (last_base >= 0) state.seed_offset = Eigen::Vector2d(qx[last_base] - bx[last_base], qy[last_base] - by[last_base]);
    state.run = run;
    return newton_count;
  }

  bool sourceJacobian(const Eigen::Vector2d&, const Eigen::Vector2d& s,
                      Eigen::Matrix2d& j) const override {
    Eigen::Vector2d f;
    Eigen::Matrix2d jf;
    if (!newton_.forward().evaluate(s, f, &jf)) return false;
    const double det = jf.determinant();
    if (!(std::abs(det) > 0.0)) return false;
    j = jf.inverse();
    return j.allFinite();
  }

 private:
  static constexpr int kQuickIterations = 8;
  static constexpr int kMaxIterations = 30;
  // Correction-grid spacing (output pixels): bilinear interpolation of the seed's error
  // misses by spacing²/8 · its curvature; 64 px measured ~1/256 px on the peer's mild lens
  // (half the pixels failing the check), 32 px a quarter of that. A divisor of kSpanPixels.
  static constexpr int kGrid = kSpanPixels / 2;

  // The forward map and its Jacobian (eq 1, 2); the one-stage case inline, chains generic.
  bool forward(const Eigen::Vector2d& s, Eigen::Vector2d& f, Eigen::Matrix2d& j,
               unsigned& signs) const {
    if (forward_q_.empty()) return newton_.forward().evaluate(s, f, &j, &signs);
    const double u = s.x(), v = s.y();
    const double den = forward_q_[2].value(u, v);
    if (!(std::abs(den) > 0.0)) return false;
    const double inv = 1.0 / den;
    const double fx = forward_q_[0].value(u, v) * inv, fy = forward_q_[1].value(u, v) * inv;
    const double du = forward_q_[2].du(u, v), dv = forward_q_[2].dv(u, v);
    j << (forward_q_[0].du(u, v) - fx * du) * inv, (forward_q_[0].dv(u, v) - fx * dv) * inv,
        (forward_q_[1].du(u, v) - fy * du) * inv, (forward_q_[1].dv(u, v) - fy * dv) * inv;
    f = Eigen::Vector2d(fx, fy);
    signs = den < 0.0 ? 1u : 0u;
    return std::isfinite(fx) && std::isfinite(fy);
  }

  // The seed check: one forward evaluation, the Newton step it implies, and the pole and fold
  // tests of inverse.h at the start.
  bool check(const Eigen::Vector2d& t, const Eigen::Vector2d& start, Eigen::Vector2d& s) const {
    Eigen::Vector2d f;
    Eigen::Matrix2d j;
    unsigned signs = 0;
    if (!forward(start, f, j, signs)) return false;
    const CentreReference& c = newton_.centre();
    const double det = j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0);
    if (signs != c.denominator_signs || (det > 0.0) != c.det_positive) return false;
    const Eigen::Vector2d r = f - t;
    const Eigen::Vector2d step(( j(1, 1) * r.x() - j(0, 1) * r.y()) / det,
                               (-j(1, 0) * r.x() + j(0, 0) * r.y()) / det);
    if (!(std::abs(step.x()) <= seed_tolerance_ && std::abs(step.y()) <= seed_tolerance_))
      return false;
    s = start - step;
    return true;
  }

  Eigen::Vector2d seedAt(const Eigen::Vector2d& t, bool& ok) const {
    ok = true;
    if (seed_q_.empty()) return t;
    const Quadratic q0(seed_q_[0]), q1(seed_q_[1]), q2(seed_q_[2]);
    const double den = q2.value(t.x(), t.y());
    const Eigen::Vector2d s = Eigen::Vector2d(q0.value(t.x(), t.y()), q1.value(t.x(), t.y())) / den;
    ok = s.allFinite();
    return s;
  }

  // The exact inverse minus the seed at nodes every kGrid output pixels (including the
  // far edge); a node with no preimage makes its cells fall back to the seed alone.
  void buildCorrectionGrid(FrameSize target_px, int threads) {
    grid_w_ = target_px.width / kGrid + 2;
    grid_h_ = target_px.height / kGrid + 2;
    nodes_.assign(static_cast<size_t>(grid_w_) * static_cast<size_t>(grid_h_), Eigen::Vector2d::Zero());
    node_valid_.assign(nodes_.size(), 0);
    ParallelOptions po;
    po.threads = threads;
    po.band_rows = 4;
    parallelForRows(grid_h_, po, [&](int j0, int j1) {
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < grid_w_; ++i) {
          const Eigen::Vector2d t(i * kGrid, j * kGrid);
          bool seeded = false;
          const Eigen::Vector2d base = seedAt(t, seeded);
          const size_t k = static_cast<size_t>(j) * static_cast<size_t>(grid_w_) + static_cast<size_t>(i);
          // The seed's error changes little from node to node: the left neighbour's correction
          // added to the seed starts Newton a step or two closer than the seed alone.
          Eigen::Vector2d s;
          bool ok = seeded && i > 0 && node_valid_[k - 1] && newton_.solve(t, base + nodes_[k - 1], s, kMaxIterations);
          if (!ok) ok = seeded && newton_.solve(t, base, s, kMaxIterations);
          if (!ok) ok = newton_.solveFromCentre(t, s, kMaxIterations);
          if (ok && seeded) {
            nodes_[k] = s - base;
            node_valid_[k] = 1;
          }
        }
    });
  }

  // Cells where seed + bilinear correction is trusted without the per-pixel check. The error
  // of bilinear interpolation in a cell of side G is about G²/8 (|d_uu| + |d_vv|) for the
  // interpolated function d = exact − seed; two independent estimates of it must both stay
  // within certify_tolerance_: the second differences of d over the neighbouring nodes, and
  // the actual miss at the cell centre (where a quadratic's interpolation error peaks) against
  // an exact Newton solution there. Cells touching a node without a preimage never qualify,
  // nor do cells where the centre's solution fails (poles, folds: inverse.h's tests).
  void certifyCells(int threads) {
    const int cw = grid_w_ - 1, ch = grid_h_ - 1;
    cell_fast_.assign(static_cast<size_t>(cw) * static_cast<size_t>(ch), 0);
    if (seed_q_.empty() || !(certify_tolerance_ > 0.0)) return;
    const auto valid_at = [&](int i, int j) {
      return i >= 0 && j >= 0 && i < grid_w_ && j < grid_h_ &&
             node_valid_[static_cast<size_t>(j) * static_cast<size_t>(grid_w_) + static_cast<size_t>(i)] != 0;
    };
    // |second difference| of d at node (i, j) along one axis; one-sided at the grid's edge.
    const auto second = [&](int i, int j, int di, int dj) {
      int ci = i, cj = j;
      if (!valid_at(i - di, j - dj)) ci += di, cj += dj;
      else if (!valid_at(i + di, j + dj)) ci -= di, cj -= dj;
      if (!valid_at(ci - di, cj - dj) || !valid_at(ci, cj) || !valid_at(ci + di, cj + dj))
        return std::numeric_limits<double>::infinity();
      const Eigen::Vector2d d2 = node(ci - di, cj - dj) - 2.0 * node(ci, cj) + node(ci + di, cj + dj);
      return d2.cwiseAbs().maxCoeff();
    };
    ParallelOptions po;
    po.threads = threads;
    po.band_rows = 4;
    parallelForRows(ch, po, [&](int j0, int j1) {
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < cw; ++i) {
          if (!cellValid(i, j)) continue;
          double curvature = 0.0;
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a)
              curvature = std::max(curvature, second(i + a, j + b, 1, 0) + second(i + a, j + b, 0, 1));
          if (!(curvature / 8.0 <= certify_tolerance_)) continue;
          const Eigen::Vector2d t((i + 0.5) * kGrid, (j + 0.5) * kGrid);
          bool seeded = false;
          const Eigen::Vector2d base = seedAt(t, seeded);
          if (!seeded) continue;
          const Eigen::Vector2d predicted =
              base + 0.25 * (node(i, j) + node(i + 1, j) + node(i, j + 1) + node(i + 1, j + 1));
          // Its miss, by the one Newton step from it (as the seed check does): exact to
          // curvature · step², ~1e-6 px at the tolerance, for one forward evaluation instead of
          // a converged Newton solve (half the kernel's set-up time).
          Eigen::Vector2d f;
          Eigen::Matrix2d jf;
          unsigned signs = 0;
          if (!forward(predicted, f, jf, signs)) continue;
          const double det = jf.determinant();
          if (signs != newton_.centre().denominator_signs || (det > 0.0) != newton_.centre().det_positive)
            continue;
          const Eigen::Vector2d r = f - t;
          const Eigen::Vector2d step((jf(1, 1) * r.x() - jf(0, 1) * r.y()) / det,
                                     (jf(0, 0) * r.y() - jf(1, 0) * r.x()) / det);
          if (!(step.cwiseAbs().maxCoeff() <= certify_tolerance_)) continue;
          cell_fast_[static_cast<size_t>(j) * static_cast<size_t>(cw) + static_cast<size_t>(i)] = 1;
        }
    });
  }

  double certifiedShare() const override {
    if (cell_fast_.empty()) return 0.0;
    long long fast = 0;
    for (unsigned char c : cell_fast_) fast += c;
    return static_cast<double>(fast) / static_cast<double>(cell_fast_.size());
  }

  bool spanCertified(int x0, int n, int gj) const {
    if (cell_fast_.empty()) return false;
    const int cw = grid_w_ - 1;
    for (int gi = x0 / kGrid; gi <= (x0 + n - 1) / kGrid; ++gi)
      if (gi >= cw || !cell_fast_[static_cast<size_t>(gj) * static_cast<size_t>(cw) + static_cast<size_t>(gi)])
        return false;
    return true;
  }

  // A span whose cells are all certified: seed + correction per cell, unchecked. Writes whole
  // cells (up to kSpanPixels entries of sx, sy, valid, past n at the row's end).
  int fastSpan(int y, int x0, int n, int gj, double fy, float* sx, float* sy, unsigned char* valid,
               RowState& state) const {
    // The seed's quadratic forms along row y, in the pixel offset i from x0 (rational_map.h).
    const double v = y + 0.5, u0 = x0 + 0.5;
    SeedRow r;
    for (int k = 0; k < 3; ++k) {
      const Quadratic& q = seed_forms_[static_cast<size_t>(k)];
      r.c[k] = q.value(u0, v);
      r.b[k] = q.du(u0, v);
      r.a[k] = q.a;
    }
    // The correction, bilinear in the cell at pixel c0: linear along the row, from the nodes
    // (gi, gj): corr(i) = left + slope · (u − gi · kGrid) at u = x0 + i + 0.5.
    const auto correction = [&](int c0) {
      const int gi = (x0 + c0) / kGrid;
      const Eigen::Vector2d left = (1 - fy) * node(gi, gj) + fy * node(gi, gj + 1);
      const Eigen::Vector2d right = (1 - fy) * node(gi + 1, gj) + fy * node(gi + 1, gj + 1);
      const Eigen::Vector2d slope = (right - left) / kGrid;
      const Eigen::Vector2d at_x0 = left + slope * (u0 - gi * kGrid);
      r.lx = at_x0.x();
      r.ly = at_x0.y();
      r.slope_x = slope.x();
      r.slope_y = slope.y();
    };
    bool done = false;
#if defined(__x86_64__)
    SeedSpanF f{};
    if (!scalar_only_ && cpuHasAvx2() && anchorSpan(r, f)) {
      for (int c0 = 0, cell = 0; c0 < n; c0 += kGrid, ++cell) {
        correction(c0);
        for (int c = cell; c < 2; ++c) {  // a span's missing second cell copies the first
          f.lx[c] = static_cast<float>(r.lx);
          f.ly[c] = static_cast<float>(r.ly);
          f.kx[c] = static_cast<float>(r.slope_x);
          f.ky[c] = static_cast<float>(r.slope_y);
        }
      }
      if (avx512_ && cpuHasAvx512f()) seedSpanFloatAvx512(f, sx, sy);
      else seedSpanFloatAvx2(f, sx, sy);
      done = true;
    }
#endif
    for (int c0 = 0; c0 < n && !done; c0 += kGrid) {
      correction(c0);
      seedCell(r, c0, sx + c0, sy + c0);
    }
    std::fill(valid, valid + std::max(n, 0), static_cast<unsigned char>(1));
    // The row state as if these pixels had been solved (their solutions are these positions).
    const auto at = [&](int j) {
      return j >= 0 ? Eigen::Vector2d(sx[j], sy[j])
                    : j == -1 ? state.previous : j == -2 ? state.before_previous : state.third;
    };
    const Eigen::Vector2d p1 = at(n - 1), p2 = at(n - 2), p3 = at(n - 3);
    state.previous = p1;
    state.before_previous = p2;
    state.third = p3;
    state.seed_offset = Eigen::Vector2d::Zero();
    state.run += n;
    return 0;
  }

  const Eigen::Vector2d& node(int i, int j) const {
    return nodes_[static_cast<size_t>(j) * static_cast<size_t>(grid_w_) + static_cast<size_t>(i)];
  }
  bool cellValid(int i, int j) const {
    const auto at = [&](int a, int b) {
      return node_valid_[static_cast<size_t>(b) * static_cast<size_t>(grid_w_) + static_cast<size_t>(a)] != 0;
    };
    return at(i, j) && at(i + 1, j) && at(i, j + 1) && at(i + 1, j + 1);
  }

  NewtonInverse newton_;
  std::vector<Eigen::Matrix3d> seed_q_;
  std::vector<Quadratic> seed_forms_;  // seed_q_ as n = a u² + b uv + …, for fastSpan
  std::vector<Quadratic> forward_q_;
  double seed_tolerance_;
  double certify_tolerance_;
  bool scalar_only_;
  bool avx512_;
  int grid_w_ = 0, grid_h_ = 0;
  std::vector<Eigen::Vector2d> nodes_;
  std::vector<unsigned char> node_valid_;
  std::vector<unsigned char> cell_fast_;  // (grid_w_ − 1) × (grid_h_ − 1) cells, certifyCells
};

Eigen::Matrix3d pixelHomography(const CameraStructure& structure, FrameSize source_px,
                                FrameSize target_px) {
  // The homography is stored normalised (frames.h); in pixels it is P_out · H · N_source.
  return pixelFromNormalizedMatrix(target_px) * Eigen::Matrix3d(structure.homography) *
         normalizedFromPixelMatrix(source_px);
}

}  // namespace

KernelChoice makeCoordinateKernel(const Camera& camera, const CameraStructure& structure,
                                  FrameSize source_px, FrameSize target_px,
                                  const CoordinateOptions& options, int threads) {
  KernelChoice choice;
  if (!options.force_rational && structure.geometry != GeometryClass::Rational) {
    const bool same_size = source_px == target_px;
    // An identity between frames of different pixel sizes is an axis-aligned scaling.
    choice.name = structure.geometry == GeometryClass::Identity
                      ? (same_size ? "identity" : "affine")
                      : std::string(geometryClassName(structure.geometry));
    choice.kernel = std::make_unique<ProjectiveKernel>(
        pixelHomography(structure, source_px, target_px), source_px, options.scalar_only);
    return choice;
  }
  choice.name = "rational";
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (options.fit_inverse_seed) {
    Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px);
    if (fitted) seed = std::move(*fitted);
    else choice.note = "inverse seed not used: " + fitted.status.message;
  }
  choice.kernel = std::make_unique<RationalKernel>(std::move(forward), std::move(seed), source_px,
                                                   target_px, options, threads);
  return choice;
}

std::unique_ptr<InverseMap> makeReferenceInverse(const Camera& camera,
                                                 const CameraStructure& structure,
                                                 FrameSize source_px, FrameSize target_px,
                                                 bool force_rational) {
  if (!force_rational && structure.geometry != GeometryClass::Rational)
    return makeHomographyInverse(pixelHomography(structure, source_px, target_px), source_px);
  // The pre-fusion production path: Newton at every pixel to ~1e-7 px, from the fitted seed,
  // the neighbours and the centre (validated against closed forms in test_kernels).
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px)) seed = std::move(*fitted);
  RationalInverseOptions ro;
  return makeRationalInverse(std::move(forward), std::move(seed), source_px, ro);
}

}  // namespace artcam
