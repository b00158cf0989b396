// SPDX-License-Identifier: Apache-2.0
// Source positions for spans of output pixels: the coordinate half of the fused warp.
// No per-pixel map is ever stored: the warp asks for one span of at most kSpanPixels output
// pixels, samples it while the positions are in L1, and moves on.
//
// Conventions: pixel frames, centres at i + 0.5 (frames.h); positions come out in SOURCE
// pixels as float (6000 px · 2⁻²⁴ ≈ 4e-4 px, ten times finer than the 1/256 px budget).
//
// Kernels, chosen once per camera from the structure analysis, so a scene
// never pays for what its camera does not need:
// - projective (identity, translation, affine, homography): the exact inverse homography,
//   evaluated at each span's start and stepped by one column of it per pixel (i · step, not
//   a running sum, so nothing drifts). Under AVX2 the span runs in float lanes re-anchored in
//   double at its first pixel, s₀ + t β / (1 + γ t) (only the offset from s₀ is float), where
//   that is exact enough (no horizon, W within 2× along the span, |s| ≤ 16384 px);
// - rational: the fitted inverse seed (inverse_seed.h) evaluated by forward differences,
//   re-anchored at every span start (drift ≈ span² · ε), plus a correction bilinear between
//   nodes of a coarse grid where the exact inverse was solved once. Along a row, once two
//   pixels are solved, their extrapolation is a closer start still (quadratic from three: its
//   error is the map's third derivative, ~1e-5 px), and after one the seed shifted by the last pixel's
//   seed error. Each start is checked by ONE forward evaluation (eq 1): r = F(s) − t,
//   δ = J⁻¹ r. When |δ| ≤ the seed tolerance and s is on the centre's side of the poles and
//   folds (inverse.h), s − δ is taken (the Newton step the check has already paid for, which
//   leaves an error ~ curvature · δ²); only pixels where every start misses run the damped
//   Newton of inverse.h. Certified cells (certify_tolerance_px, inverse_cells.h) skip the check:
//   their float patch (CellPoly, an offset from an anchor) is evaluated by fused multiply-adds,
//   sixteen lanes under AVX-512, eight under AVX2, bit-identical to the scalar code. The SIMD
//   lanes are tested against the scalar code (≤ 1e-3 px) and the exact inverse;
// - rational and central (radial lenses; with the centre at infinity, the twist:
//   central_inverse.h): the certified cells as above, and where a cell fails (near a fold or
//   pole) the closed-form inverse per pixel, a root of a quadratic, instead of the quadtree and
//   Newton.
#pragma once

#include "core/model/camera.h"
#include "core/model/structure.h"
#include "core/mapping/inverse.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <optional>
#include <string>

namespace artcam {

// Pixels per span (a whole number of the rational kernel's cells). 256, not 64: each span
// pays fixed costs — a kernel's anchor in double and set-up, the sampler's constants, and
// the sampler's first loads of positions stored moments before (still in the store buffer) —
// which 256 pixels spread thin, while sx, sy and valid for a span are 2.3 KB, well inside L1.
constexpr int kSpanPixels = 256;

struct CoordinateOptions {
  // Newton's acceptance: the preimage must map within this of the output pixel centre.
  double residual_tolerance_px = 1e-3;
  // The seed check: a seed whose Newton step is at most this long (source pixels) is accepted
  // after that one step; longer ones run the full Newton.
  double seed_tolerance_px = 1.0 / 256.0;
  // The rational kernel's certified cells (source pixels): where the grid's own estimates of
  // the seed + correction error stay within this, pixels take seed + correction unchecked
  // (no forward evaluation, one division). 0 turns certification off (every pixel checked).
  double certify_tolerance_px = 1.0 / 4096.0;
  bool fit_inverse_seed = true;
  bool force_rational = false;  // run the rational kernel on projective cameras (tests, bench)
  // Run the portable scalar code where a SIMD clone exists (tests and the benchmark compare).
  bool scalar_only = false;
  // Let certified rational cells and the warp's samplers take the AVX-512 lanes where the CPU
  // has them (false: AVX2; both give the scalar code's positions and pixels bit for bit).
  bool allow_avx512 = true;
  // Central maps (radial lenses, and twists with their centre at infinity: central_inverse.h)
  // take their closed-form inverse where the rational kernel's cells do not certify; false
  // sends them down the general path (tests compare the two).
  bool central_inverse = true;
};

// What the rational kernel carries along a row from span to span: the last solutions, whose
// extrapolation is the best start of all (the map is smooth at the scale of a pixel). Reset
// (default-construct) at the start of every row and ask for a row's spans left to right, so
// every row comes out the same whatever thread renders it.
struct RowState {
  Eigen::Vector2d previous{0, 0}, before_previous{0, 0}, third{0, 0};
  Eigen::Vector2d seed_offset{0, 0};  // solution − seed at the last pixel solved from the seed
  int run = 0;                        // consecutive solved pixels just before this one
  // > 0: previous, before_previous and third are not written yet; they are the rational
  // kernel's certified positions at pixels certified_end − 1, − 2, − 3 of this row, worked out
  // again only when a span needs them (most spans of a certified row never do).
  int certified_end = 0;
};

class CoordinateKernel {
 public:
  virtual ~CoordinateKernel() = default;
  // Source positions of output pixel centres (x0 + i + 0.5, y + 0.5), i in [0, n), with
  // n ≤ kSpanPixels and x0 a multiple of kSpanPixels. valid[i] = 0: no preimage (sx, sy then
  // unspecified). sx, sy and valid must have room for kSpanPixels entries (entries past n may
  // be written). Returns how many pixels needed the full Newton. Thread-safe.
  virtual int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
                   RowState& state) const = 0;
  // d source / d target (column form) at output point t whose preimage is s; false where the
  // map is singular there.
  virtual bool sourceJacobian(const Eigen::Vector2d& t, const Eigen::Vector2d& s,
                              Eigen::Matrix2d& j) const = 0;
  // The share of the output the rational kernel certified (coordinates.h, certifyCells): its
  // pixels skip the per-pixel check. 0 for the exact projective kernels.
  virtual double certifiedShare() const { return 0.0; }
  // source = target + offset for a translation by whole pixels (then the warp copies rows).
  virtual std::optional<std::array<int, 2>> wholePixelOffset() const { return std::nullopt; }
};

struct KernelChoice {
  std::unique_ptr<CoordinateKernel> kernel;
  std::string name;  // "identity", "translation", "affine", "homography", "rational"
  std::string note;  // e.g. why the inverse seed was not used
};

// Throws std::invalid_argument for a camera the gather warp cannot invert (warp.h).
KernelChoice makeCoordinateKernel(const Camera& camera, const CameraStructure& structure,
                                  FrameSize source_px, FrameSize target_px,
                                  const CoordinateOptions& options, int threads = 0);

// The exact double-precision reference the tests and the benchmark compare positions with:
// the inverse homography for projective cameras, else Newton per pixel to ~1e-7 px from
// robust starts (inverse.h), with no seed and no float.
std::unique_ptr<InverseMap> makeReferenceInverse(const Camera& camera,
                                                 const CameraStructure& structure,
                                                 FrameSize source_px, FrameSize target_px,
                                                 bool force_rational = false);

}  // namespace artcam
