// SPDX-License-Identifier: Apache-2.0
// The coordinate kernel of identity, translation, affine and homography cameras
// (projective_kernel.h): the inverse homography span by span, in closed form.
#include "core/mapping/projective_kernel.h"

#include "core/util/cpu_features.h"

#include <Eigen/LU>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

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
#if defined(__x86_64__)
    affine_lanes_ = affine_ && !scalar_only_ && cpuHasAvx2();
#endif
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState&) const override {
#if defined(__x86_64__)
    // Affine maps (W = 1 exactly, γ = 0): the float lanes, set up without the divisions below,
    // which by W = 1 would give these same numbers, and before anything else (chromatic
    // aberration runs three of these per pixel, so their set-up counts).
    if (affine_lanes_) {
      const double u0 = m_(0, 0) * (x0 + 0.5) + m_(0, 1) * (y + 0.5) + m_(0, 2);
      const double v0 = m_(1, 0) * (x0 + 0.5) + m_(1, 1) * (y + 0.5) + m_(1, 2);
      const double u1 = u0 + (n - 1) * m_(0, 0), v1 = v0 + (n - 1) * m_(1, 0);
      if (std::max(std::max(std::abs(u0), std::abs(v0)), std::max(std::abs(u1), std::abs(v1))) <= kFloatSpanLimit) {
        const ProjectiveSpanF f{static_cast<float>(u0), static_cast<float>(v0), static_cast<float>(m_(0, 0)),
                                static_cast<float>(m_(1, 0)), 0.0f};
        projectiveSpanFloatAvx2<true>(f, sx, sy);
        std::memset(valid, 1, static_cast<size_t>(n));
        return 0;
      }
    }
#endif
    const Eigen::Vector3d h0 = m_ * Eigen::Vector3d(x0 + 0.5, y + 0.5, 1.0);
    const double dx = m_(0, 0), dy = m_(1, 0), dw = m_(2, 0);
    const ProjectiveRow r{h0.x(), h0.y(), h0.z(), dx, dy, dw, centre_positive_ ? 1.0 : -1.0};
#if defined(__x86_64__)
    // Homographies, and affine maps too: the float lanes beat the double loops below.
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
  bool affine_lanes_ = false;  // affine, SIMD allowed and present: span's first path
  bool centre_positive_ = true;
};

}  // namespace

std::unique_ptr<CoordinateKernel> makeProjectiveKernel(const Eigen::Matrix3d& target_from_source,
                                                       FrameSize source_px, bool scalar_only) {
  return std::make_unique<ProjectiveKernel>(target_from_source, source_px, scalar_only);
}

}  // namespace artcam
