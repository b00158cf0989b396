// SPDX-License-Identifier: Apache-2.0
// The rational kernel (rational_kernel.h): certified cells, the seed check and per-pixel Newton.
#include "core/mapping/rational_kernel.h"

#include "core/mapping/central_inverse.h"
#include "core/mapping/inverse_cells.h"
#include "core/model/frames.h"
#include "core/util/cpu_features.h"
#include "core/util/parallel.h"

#include <Eigen/LU>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

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

// The seed check (RationalKernel::check) for kCheckLanes starts in plain doubles without
// branches, so it vectorises: q = start − δ, passed = 1 where the check accepts. A span runs it
// only on the groups of lanes that hold a pixel to check (certified subcells need none).
// checkSpanAvx2 (rational_kernel_avx2.h) is this body compiled for AVX2, chosen when the kernel
// is made (cpu_features.h); checkSpanScalar is the fallback machines without AVX2 run, and
// CoordinateOptions::scalar_only forces it so the tests compare the two (no FMA in either, so
// they agree bit for bit).
constexpr int kCheckLanes = 8;
static_assert(kSpanPixels % kCheckLanes == 0, "a span holds whole groups of lanes");

[[gnu::always_inline]] inline void checkSpanBody(
    const CheckInputs& in, double tx0, double ty, const double* __restrict bx,
    const double* __restrict by, double* __restrict qx, double* __restrict qy,
    std::int64_t* __restrict passed) {
  const Quadratic f0 = in.f0, f1 = in.f1, f2 = in.f2;
  for (int i = 0; i < kCheckLanes; ++i) {
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


void checkSpanScalar(const CheckInputs& in, double tx0, double ty, const double* bx,
                     const double* by, double* qx, double* qy, std::int64_t* passed) {
  checkSpanBody(in, tx0, ty, bx, by, qx, qy, passed);
}

constexpr int kCellPixels = InverseCells::kCell;
static_assert(kSpanPixels % kCellPixels == 0, "a span holds whole cells");

// A certified cell's pixels on row v (local, 0 … 1) from its float patch (CellPoly): the row's
// cubic by Horner in v, k_i = p0 + v (p1 + v (p2 + v p3)) per lane, then at u_j = (j + 0.5) /
// kCell the cubic in u plus the anchor. Every step is a fused multiply-add, which rounds once
// whatever the vector width: the scalar code (std::fma), the AVX2 and the AVX-512 lanes agree
// bit for bit, and a pixel can be recomputed alone (polyPixel) exactly as its span wrote it.
// Fused, a position costs four instructions per axis instead of seven, which at every pixel
// of a certified frame is not small beside the patch rows themselves.
[[gnu::always_inline]] inline float polyLane(const CellPoly& c, float v, int i) {
  return std::fma(v, std::fma(v, std::fma(v, c.p[3][i], c.p[2][i]), c.p[1][i]), c.p[0][i]);
}

[[gnu::always_inline]] inline constexpr float polyU(int j) {
  return (static_cast<float>(j) + 0.5f) * (1.0f / kCellPixels);
}

// polyU of every pixel of a cell, for the SIMD kernels to load (exact, as polyU: j + 0.5 and
// the power of two are exact in float), made once rather than at every call.
struct CellU {
  alignas(64) float u[kCellPixels];
  constexpr CellU() : u{} {
    for (int j = 0; j < kCellPixels; ++j) u[j] = polyU(j);
  }
};
constexpr CellU kCellU;

[[gnu::always_inline]] inline void polyCellBody(const CellPoly& c, float v, float* sx, float* sy) {
  float k[8];
  for (int i = 0; i < 8; ++i) k[i] = polyLane(c, v, i);
  for (int j = 0; j < kCellPixels; ++j) {
    const float u = polyU(j);
    sx[j] = c.anchor_x + std::fma(u, std::fma(u, std::fma(u, k[3], k[2]), k[1]), k[0]);
    sy[j] = c.anchor_y + std::fma(u, std::fma(u, std::fma(u, k[7], k[6]), k[5]), k[4]);
  }
}

// Scalar: std::fma, a library call on the x86-64 baseline; polyCellFma (rational_kernel_avx2.h)
// is the same loop with the FMA instruction, and the same results.
void polyCellScalar(const CellPoly& c, float v, float* sx, float* sy) { polyCellBody(c, v, sx, sy); }

// Pixel j of the cell's row v, as polyCellScalar and the SIMD lanes write it.
void polyPixel(const CellPoly& c, float v, int j, Eigen::Vector2d& s) {
  float k[8];
  for (int i = 0; i < 8; ++i) k[i] = polyLane(c, v, i);
  const float u = polyU(j);
  s = Eigen::Vector2d(c.anchor_x + std::fma(u, std::fma(u, std::fma(u, k[3], k[2]), k[1]), k[0]),
                      c.anchor_y + std::fma(u, std::fma(u, std::fma(u, k[7], k[6]), k[5]), k[4]));
}

// A certified square of an open cell's quadtree (InverseCells::SubSquare), pixels j0 … j0 +
// count − 1 of its row v: as a cell's, with u_j = (j + 0.5) · scale where scale = 1 / the
// square's side, a power of two as 1 / kCell is, so u is exact and every lane agrees bit for bit.
[[gnu::always_inline]] inline void polySquareBody(const CellPoly& c, float v, float scale, int j0,
                                                  int count, float* sx, float* sy) {
  float k[8];
  for (int i = 0; i < 8; ++i) k[i] = polyLane(c, v, i);
  for (int j = 0; j < count; ++j) {
    const float u = (static_cast<float>(j0 + j) + 0.5f) * scale;
    sx[j] = c.anchor_x + std::fma(u, std::fma(u, std::fma(u, k[3], k[2]), k[1]), k[0]);
    sy[j] = c.anchor_y + std::fma(u, std::fma(u, std::fma(u, k[7], k[6]), k[5]), k[4]);
  }
}

void polySquareScalar(const CellPoly& c, float v, float scale, int j0, int count, float* sx,
                      float* sy) {
  polySquareBody(c, v, scale, j0, count, sx, sy);
}

#if defined(__x86_64__)
#include "core/mapping/rational_kernel_avx2.h"
#include "core/mapping/rational_kernel_avx512.h"
#endif

// The patch in double at pixel j of the cell (the per-pixel path's start).
Eigen::Vector2d cubicAt(const CellRow& r, int j, int size = kCellPixels) {
  const double u = (j + 0.5) / size;
  return {r.x[0] + u * (r.x[1] + u * (r.x[2] + u * r.x[3])),
          r.y[0] + u * (r.y[1] + u * (r.y[2] + u * r.y[3]))};
}

class RationalKernel final : public CoordinateKernel {
 public:
  RationalKernel(RationalMap forward, std::optional<RationalMap> seed, FrameSize source_px,
                 FrameSize target_px, const CoordinateOptions& options, int threads)
      : newton_(std::move(forward), source_px, options.residual_tolerance_px),
        seed_(std::move(seed)),
        seed_tolerance_(options.seed_tolerance_px),
        scalar_only_(options.scalar_only) {
#if defined(__x86_64__)
    if (!scalar_only_ && cpuHasAvx2() && cpuHasFma())
      cells_simd_ = options.allow_avx512 && cpuHasAvx512f() ? 2 : 1;
    check_avx2_ = !scalar_only_ && cpuHasAvx2();
    fma_scalar_ = !scalar_only_ && cpuHasFma();
#endif
    if (seed_ && seed_->stageCount() == 1) seed_q_ = seed_->stage(0);
    if (newton_.forward().stageCount() == 1)
      for (const Eigen::Matrix3d& q : newton_.forward().stage(0)) forward_q_.emplace_back(q);
    InverseCellsOptions co;
    // 0 turns certification off: every pixel takes the per-pixel path (tests compare).
    co.certify_tolerance_px = options.certify_tolerance_px > 0.0 ? options.certify_tolerance_px : -1.0;
    co.threads = threads;
    // A central map's open cells take its closed-form inverse per pixel (central_inverse.h),
    // which costs less than refining them would: no quadtree, no per-pixel Newton.
    if (options.central_inverse)
      central_ = CentralInverse::detect(newton_.forward(), source_px, newton_.centre());
    if (central_) co.subdivide = false;
    central_simd_ = scalar_only_ ? 0 : options.allow_avx512 ? 2 : 1;
    cells_.emplace(newton_, seed_ ? &*seed_ : nullptr, source_px, target_px, co);
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState& state) const override {
    // The span in runs of subcells: those whose row has a pixel for the per-pixel path
    // (mixedSpan, in double, checked) apart from the rest, so that one open subcell sends only
    // its own kSub pixels, not its cell's or the span's, down the slow path.
    const InverseCells& cells = *cells_;
    constexpr int kSub = InverseCells::kSub;
    const int cy = std::min(y / kCellPixels, cells.cellsHigh() - 1);
    // Nearly every span of a lens lies in certified cells: straight to their patches, without
    // the runs below.
    if (x0 % kCellPixels == 0) {
      const int first = x0 / kCellPixels, last = std::min((x0 + n - 1) / kCellPixels, cells.cellsWide() - 1);
      bool certified = true;
      for (int cx = first; cx <= last && certified; ++cx) certified = cells.kind(cx, cy) == InverseCells::kCertified;
      if (certified) return patchedRun(y, x0, n, sx, sy, valid, state);
    }
    const int sub_y = std::min((y - cy * kCellPixels) / kSub, InverseCells::kSubs - 1);
    const int units = (n + kSub - 1) / kSub;
    // Bit k: subcell column k of the span needs no check (a mask, not an array of flags: bytes
    // written in a fill and read back one by one stall on store forwarding).
    static_assert(kSpanPixels / kSub <= 32, "a span's subcells fit a 32-bit mask");
    std::uint32_t patched = 0;
    for (int k = 0; k < units;) {
      const int x = x0 + k * kSub, cx = std::min(x / kCellPixels, cells.cellsWide() - 1);
      const int end = std::min(units, k + (cx + 1) * InverseCells::kSubs - x / kSub);
      const InverseCells::Kind kind = cells.kind(cx, cy);
      if (kind != InverseCells::kOpen) {
        patched |= static_cast<std::uint32_t>((std::uint64_t{1} << end) - (std::uint64_t{1} << k));
      } else if (cells.refined(cx, cy)) {
        for (int j = k; j < end; ++j)
          if (cells.subKind(cx, cy, (x0 + j * kSub - cx * kCellPixels) / kSub, sub_y) != InverseCells::kOpen)
            patched |= std::uint32_t{1} << j;
      }
      k = end;
    }
    int newton = 0;
    for (int k0 = 0; k0 < units;) {
      const bool p = (patched >> k0) & 1u;
      // The run ends at the next bit that differs (or the span's end).
      const std::uint64_t rest = (p ? ~std::uint64_t{patched} : std::uint64_t{patched}) >> k0;
      const int k1 = std::min(units, k0 + (rest ? __builtin_ctzll(rest) : 64));
      const int a = k0 * kSub, b = std::min(n, k1 * kSub);
      if (p)
        newton += patchedRun(y, x0 + a, b - a, sx + a, sy + a, valid + a, state);
      else if (central_)
        centralRun(y, x0 + a, b - a, sx + a, sy + a, valid + a, state);
      else
        newton += mixedSpan(y, x0 + a, b - a, sx + a, sy + a, valid + a, state);
      k0 = k1;
    }
    return newton;
  }

  // Pixels x0 … x0 + n − 1 of row y in certified and empty cells and subcells only (span
  // above): no pixel needs a check. The run starts on a subcell and holds whole cells but
  // where a refined cell cuts it (and at the frame's right edge).
  int patchedRun(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
                 RowState& state) const {
    const InverseCells& cells = *cells_;
    const int cy = std::min(y / kCellPixels, cells.cellsHigh() - 1);
    const int first = x0 / kCellPixels, count = (x0 + n - 1) / kCellPixels - first + 1;
    bool all_certified = x0 % kCellPixels == 0, all_empty = true;
    for (int k = 0; k < count; ++k) {
      const InverseCells::Kind kind = cells.kind(std::min(first + k, cells.cellsWide() - 1), cy);
      all_certified = all_certified && kind == InverseCells::kCertified;
      all_empty = all_empty && kind == InverseCells::kEmpty;
    }
    if (all_empty) {
      std::memset(valid, 0, static_cast<size_t>(n));
      state.run = 0;
      return 0;
    }
    int tail = 0;  // solved pixels at the run's end, counted as they are written
    if (all_certified) {
      certifiedCells(first, count, y, sx, sy);
      std::memset(valid, 1, static_cast<size_t>(n));
      tail = n;
      if (n >= 3) {
        // The row state names these pixels instead of copying them (settle).
        state.certified_end = x0 + n;
        state.seed_offset = Eigen::Vector2d::Zero();
        state.run += n;
        return 0;
      }
    } else {
      for (int c0 = 0; c0 < n;) {
        const int cx = std::min((x0 + c0) / kCellPixels, cells.cellsWide() - 1);
        const int c1 = std::min(n, (cx + 1) * kCellPixels - x0);
        switch (cells.kind(cx, cy)) {
          case InverseCells::kCertified:
            // Whole: only a refined cell cuts a run (the frame's edge clips the last cell,
            // whose pixels beyond it the span's buffers hold).
            certifiedCells(cx, 1, y, sx + c0, sy + c0);
            std::memset(valid + c0, 1, static_cast<size_t>(c1 - c0));
            tail += c1 - c0;
            break;
          case InverseCells::kEmpty:
            emptyPixels(c0, c1, sx, sy, valid);
            tail = 0;
            break;
          case InverseCells::kOpen:
            subcellRow(cx, cy, y, x0, c0, c1, sx, sy, valid, tail);
            break;
        }
        c0 = c1;
      }
    }
    // The row state as if these pixels had been solved (their solutions are these positions).
    settle(y, state);
    const auto at = [&](int j) {
      return j >= 0 ? Eigen::Vector2d(sx[j], sy[j])
                    : j == -1 ? state.previous : j == -2 ? state.before_previous : state.third;
    };
    const Eigen::Vector2d p1 = at(n - 1), p2 = at(n - 2), p3 = at(n - 3);
    state.previous = p1;
    state.before_previous = p2;
    state.third = p3;
    state.seed_offset = Eigen::Vector2d::Zero();
    state.run = tail == n ? state.run + n : tail;
    return 0;
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

  double certifiedShare() const override { return cells_->certifiedShare(); }

 private:
  static constexpr int kQuickIterations = 8;
  static constexpr int kMaxIterations = 30;

  // A row state that names certified pixels (RowState::certified_end) gets their positions,
  // recomputed as the span wrote them (polyPixel).
  void settle(int y, RowState& state) const {
    if (state.certified_end <= 0) return;
    const int cy = std::min(y / kCellPixels, cells_->cellsHigh() - 1);
    const float v = (static_cast<float>(y - cy * kCellPixels) + 0.5f) * (1.0f / kCellPixels);
    Eigen::Vector2d* const slots[3] = {&state.previous, &state.before_previous, &state.third};
    for (int k = 0; k < 3; ++k) {
      const int x = state.certified_end - 1 - k, cx = x / kCellPixels;
      polyPixel(cells_->poly(cx, cy), v, x - cx * kCellPixels, *slots[k]);
    }
    state.certified_end = 0;
  }

  // Certified cells cx … cx + count − 1 of y's cell row: their patches along row y, in float.
  void certifiedCells(int cx, int count, int y, float* sx, float* sy) const {
    const int cy = std::min(y / kCellPixels, cells_->cellsHigh() - 1);
    const float v = (static_cast<float>(y - cy * kCellPixels) + 0.5f) * (1.0f / kCellPixels);
    const CellPoly* polys = &cells_->poly(cx, cy);
#if defined(__x86_64__)
    if (cells_simd_ == 2) return polyCellsAvx512(polys, count, v, sx, sy);
    if (cells_simd_ == 1) return polyCellsAvx2(polys, count, v, sx, sy);
#endif
    const auto cell = fma_scalar_ ? polyCellFma : polyCellScalar;
    for (int k = 0; k < count; ++k) cell(polys[k], v, sx + k * kCellPixels, sy + k * kCellPixels);
  }

  static void emptyPixels(int i0, int i1, float* sx, float* sy, unsigned char* valid) {
    const size_t count = static_cast<size_t>(i1 - i0);
    std::memset(valid + i0, 0, count);
    std::memset(sx + i0, 0, count * sizeof(float));
    std::memset(sy + i0, 0, count * sizeof(float));
  }

  // Pixels i0 … i1 − 1 (from x0) of row y in refined cell (cx, cy), whose subcells there are
  // certified or empty: each certified square's row from its float patch, once per square.
  // `tail` counts the solved pixels at the end of what is written.
  void subcellRow(int cx, int cy, int y, int x0, int i0, int i1, float* sx, float* sy,
                  unsigned char* valid, int& tail) const {
    const InverseCells& cells = *cells_;
    constexpr int kSub = InverseCells::kSub;
    const int sub_y = std::min((y - cy * kCellPixels) / kSub, InverseCells::kSubs - 1);
    for (int s0 = i0; s0 < i1;) {
      const int sub_x = (x0 + s0 - cx * kCellPixels) / kSub;
      if (cells.subKind(cx, cy, sub_x, sub_y) == InverseCells::kEmpty) {
        const int s1 = std::min(i1, cx * kCellPixels + (sub_x + 1) * kSub - x0);
        emptyPixels(s0, s1, sx, sy, valid);
        tail = 0;
        s0 = s1;
        continue;
      }
      const InverseCells::SubSquare q = cells.subSquare(cx, cy, sub_x, sub_y);
      const int s1 = std::min(i1, q.x0 + q.size - x0);
      squarePixels(q, y, x0 + s0 - q.x0, s1 - s0, sx + s0, sy + s0);
      std::memset(valid + s0, 1, static_cast<size_t>(s1 - s0));
      tail += s1 - s0;
      s0 = s1;
    }
  }

  // Pixels j0 … j0 + count − 1 of certified square q's row y, in float like a cell's.
  void squarePixels(const InverseCells::SubSquare& q, int y, int j0, int count, float* sx,
                    float* sy) const {
    const float scale = 1.0f / static_cast<float>(q.size);
    const float v = (static_cast<float>(y - q.y0) + 0.5f) * scale;
#if defined(__x86_64__)
    if (cells_simd_ > 0) return polySquareAvx2(*q.poly, v, scale, j0, count, sx, sy);
#endif
    (fma_scalar_ ? polySquareFma : polySquareScalar)(*q.poly, v, scale, j0, count, sx, sy);
  }

  // A run span() found unpatched, of a central map: its closed-form inverse per pixel. The row
  // state's solutions feed only the per-pixel path's starts, which a central map never takes:
  // it is left as after a run with no solved pixel.
  void centralRun(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
                  RowState& state) const {
    central_->span(y, x0, n, sx, sy, valid, central_simd_);
    state.certified_end = 0;
    state.run = 0;
  }

  // The per-pixel path on a run span() found unpatched: open subcells of refined cells and
  // open cells left whole, never a certified or empty cell or subcell. Pixels in uncovered
  // blocks are transparent; the rest are checked from the best start (their subcell's patch,
  // else their cell's, else the fitted seed), and those the start misses are solved.
  int mixedSpan(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
                RowState& state) const {
    settle(y, state);
    const InverseCells& cells = *cells_;
    const double ty = y + 0.5;
    const int cy = std::min(y / kCellPixels, cells.cellsHigh() - 1);
    const int sub_y = std::min((y - cy * kCellPixels) / InverseCells::kSub, InverseCells::kSubs - 1);
    enum : unsigned char { kCheck = 0, kSkip = 1 };
    double bx[kSpanPixels], by[kSpanPixels], qx[kSpanPixels], qy[kSpanPixels];
    unsigned char mode[kSpanPixels], have[kSpanPixels], passed[kSpanPixels];
    bool need_seed = false;
    // The run may start and end inside a cell (span): positions are relative to x0.
    for (int c0 = 0, c1 = 0; c0 < n; c0 = c1) {
      const int cx = std::min((x0 + c0) / kCellPixels, cells.cellsWide() - 1);
      const int cell_x = cx * kCellPixels;
      c1 = std::min(n, cell_x + kCellPixels - x0);
      const bool refined = cells.refined(cx, cy), patch = cells.hasPatch(cx, cy);
      CellRow r{};
      bool have_row = false;  // r, made only for pixels that start from the cell's patch
      // A refined cell subcell by subcell (each with its own patch), an unrefined one whole.
      for (int s0 = c0, s1 = c0; s0 < c1; s0 = s1) {
        const int sub_x = (x0 + s0 - cell_x) / InverseCells::kSub;
        s1 = refined ? std::min(c1, cell_x + (sub_x + 1) * InverseCells::kSub - x0) : c1;
        const bool sub_patch = refined && cells.hasSubPatch(cx, cy, sub_x, sub_y);
        InverseCells::SubRow sr{};
        if (sub_patch) cells.subRow(cx, sub_x, y, sr);
        if (!sub_patch && patch && !have_row) cells.row(cx, y, r), have_row = true;
        unsigned char covered[kCellPixels];
        cells.coveredRun(x0 + s0, y, s1 - s0, covered);
        for (int i = s0; i < s1; ++i) {
          mode[i] = covered[i - s0] ? kCheck : kSkip;
          if (sub_patch || patch) {
            const Eigen::Vector2d s = sub_patch ? cubicAt(sr.cubic, x0 + i - sr.x0, sr.size)
                                                : cubicAt(r, x0 + i - cell_x);
            bx[i] = s.x();
            by[i] = s.y();
          } else {
            bx[i] = by[i] = std::numeric_limits<double>::quiet_NaN();
            need_seed = need_seed || mode[i] == kCheck;
          }
        }
      }
    }
    if (need_seed) {
      // Forward differences of the fitted inverse seed (two adds a pixel) where no patch is.
      if (!seed_q_.empty()) {
        const RowQuadratics seed_row(seed_q_, y, x0);
        double n0 = seed_row.numerator(0), n1 = seed_row.numerator(1), n2 = seed_row.numerator(2);
        double d0 = seed_row.delta(0), d1 = seed_row.delta(1), d2 = seed_row.delta(2);
        const double s0 = seed_row.second(0), s1 = seed_row.second(1), s2 = seed_row.second(2);
        for (int i = 0; i < n; ++i) {
          if (std::isnan(bx[i]) && mode[i] == kCheck) {
            bx[i] = n0 / n2;
            by[i] = n1 / n2;
          }
          n0 += d0, n1 += d1, n2 += d2;
          d0 += s0, d1 += s1, d2 += s2;
        }
      } else {
        for (int i = 0; i < n; ++i)
          if (std::isnan(bx[i]) && mode[i] == kCheck) bx[i] = x0 + i + 0.5, by[i] = ty;
      }
    }
    for (int i = 0; i < n; ++i) have[i] = mode[i] != kSkip && std::isfinite(bx[i]) && std::isfinite(by[i]);
    if (forward_q_.size() == 3) {
      const int lanes = (n + kCheckLanes - 1) / kCheckLanes * kCheckLanes;
      for (int i = 0; i < lanes; ++i)
        if (i >= n || !have[i]) bx[i] = by[i] = 0.0;  // the kernel runs all lanes
      std::int64_t accepted[kSpanPixels];
      const CheckInputs in{forward_q_[0], forward_q_[1], forward_q_[2],
                           (newton_.centre().denominator_signs & 1u) != 0,
                           newton_.centre().det_positive, seed_tolerance_};
      for (int c = 0; c < n; c += kCheckLanes) {
        bool any = false;
        for (int i = c; i < std::min(n, c + kCheckLanes); ++i)
          any = any || (have[i] && mode[i] == kCheck);
        if (!any) {
          std::fill(accepted + c, accepted + c + kCheckLanes, std::int64_t{0});
          continue;
        }
        (check_avx2_ ? checkSpanAvx2 : checkSpanScalar)(in, x0 + c + 0.5, ty, bx + c, by + c,
                                                               qx + c, qy + c, accepted + c);
      }
      for (int i = 0; i < n; ++i) passed[i] = have[i] && mode[i] == kCheck && accepted[i] != 0;
    } else {
      for (int i = 0; i < n; ++i) {
        Eigen::Vector2d q(0, 0);
        passed[i] = have[i] && mode[i] == kCheck &&
                    check(Eigen::Vector2d(x0 + i + 0.5, ty), Eigen::Vector2d(bx[i], by[i]), q);
        qx[i] = q.x();
        qy[i] = q.y();
      }
    }

    // Pass 2, in order along the row: the pixels the start missed try the extrapolation of
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
      if (mode[i] == kSkip) {
        valid[i] = 0;
        sx[i] = sy[i] = 0.0f;
        run = 0;
        continue;
      }
      const Eigen::Vector2d t(x0 + i + 0.5, ty);
      const Eigen::Vector2d base(bx[i], by[i]);
      const Eigen::Vector2d previous = solution(i - 1), before_previous = solution(i - 2);
      const Eigen::Vector2d seed_offset =
          last_base >= 0 ? Eigen::Vector2d(qx[last_base] - bx[last_base], qy[last_base] - by[last_base])
                         : before.seed_offset;
      Eigen::Vector2d s;
      bool ok = false, from_base = false, one_step = false;
      // The pixel's patch start moved by the offset the last one solved from its start needed:
      // checked, and where the check's step is too long Newton goes on from it. Open subcells
      // lie near folds and poles, where a row's solutions bend too fast to extrapolate (on the
      // strong barrel the extrapolation's check passed 100 of 73k pixels, this one 23k).
      const bool offset_start = have[i] && run >= 1;
      if (offset_start) {
        ok = from_base = newton_.acceptOrSolve(t, base + seed_offset, s, kQuickIterations,
                                               seed_tolerance_, one_step);
        if (!one_step) ++newton_count;
      } else {
        // Quadratic extrapolation of the last three solutions misses by the map's third
        // derivative (~1e-5 px); linear by its second, which strong lenses make ~1e-2 px.
        if (run >= 3) ok = check(t, 3.0 * (previous - before_previous) + solution(i - 3), s);
        if (!ok && run == 2) ok = check(t, 2.0 * previous - before_previous, s);
        if (!ok) ++newton_count;
      }
      if (!ok) {
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

  // The check: one forward evaluation, the Newton step it implies, and the pole and fold
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

  NewtonInverse newton_;
  std::optional<RationalMap> seed_;
  std::vector<Eigen::Matrix3d> seed_q_;
  std::vector<Quadratic> forward_q_;
  double seed_tolerance_;
  bool scalar_only_;
  // The certified cells' lanes: 0 scalar, 1 AVX2, 2 AVX-512 (CoordinateOptions::allow_avx512).
  int cells_simd_ = 0;
  bool check_avx2_ = false;  // the seed check's AVX2 lanes (same bits as the scalar ones)
  bool fma_scalar_ = false;  // the scalar cell loops with the FMA instruction (same bits)
  std::optional<CentralInverse> central_;
  int central_simd_ = 0;  // CentralInverse::span's lanes
  std::optional<InverseCells> cells_;  // built last: it refers to newton_ and seed_
};

}  // namespace

std::unique_ptr<CoordinateKernel> makeRationalKernel(RationalMap forward, std::optional<RationalMap> seed,
                                                     FrameSize source_px, FrameSize target_px,
                                                     const CoordinateOptions& options, int threads) {
  return std::make_unique<RationalKernel>(std::move(forward), std::move(seed), source_px, target_px,
                                          options, threads);
}

}  // namespace artcam
