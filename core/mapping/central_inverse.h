// SPDX-License-Identifier: Apache-2.0
// The closed-form inverse of a central rational map: one whose every output moves along a ray
// from a fixed target point, as radial lenses do. The division model u' = u / (1 − k|u|²) (the
// barrel and pin-cushion presets, the rational lens camera's radial member) is one; so is any
// such lens seen through affine pixel frames on both sides. With the target point at infinity
// (outputs moving along parallel lines, as the twist preset's do) it is the parallel form below.
//
// The form (one stage, eq 1 in pixel frames, x̃ = (x, 1)):
//   F(s) = c_t + (H s̃) · (l · s̃) / (s̃ᵀ Q s̃),   H a 2×3 map with an invertible 2×2 part,
// i.e. both numerators, less c_t times the denominator, share the linear factor l (the same
// factorisation structure.h uses to find homographies). The source point with H s̃ = 0 is the
// map's centre c_s (it maps to c_t). For output t, let d = t − c_t and e = H₂⁻¹ d: the points
// mapped along d form the line s(μ) = c_s + μ e, on which H s̃ = μ d, so F(s(μ)) = t reads
//   μ (l · s̃(μ)) = s̃(μ)ᵀ Q s̃(μ),  i.e.  P(μ) = (α − A) μ² + (β − 2B) μ − C = 0
// with α = l₂ · e, β = l · c̃_s, A = eᵀ Q₂ e, B = eᵀ (Q c̃_s)₂, C = c̃_sᵀ Q c̃_s: at most two
// preimages, each a root of a quadratic, instead of a Newton solve (or, near a fold, a
// quadtree of certified patches, whose cubics cannot follow the inverse's square-root
// behaviour there and so refine far into a strong barrel's frame).
//
// Which root is the preimage: inverse.h's rule, the same test Newton's solution must pass —
// on the source centre's side of the pole curve and in its fold. Both signs come from the
// root without evaluating the map: at a root, the denominator is μ (l · s̃) and the Jacobian
// determinant is det H₂ · P′(μ) / (μ² (l · s̃)) (the matrix determinant lemma on
// J = w H₂ + (H s̃) ∇wᵀ, w = (l · s̃) / (s̃ᵀ Q s̃)). The root −2C / (p₁ + sgn(p₁) √D), the one
// that stays finite as the output nears c_t (the radial lenses' every preimage), is tried
// first; where it fails the tests the other is. Where both would pass (a map whose centre c_s
// is not the frame's, both on the centre's side), the first is taken: either is a preimage
// by the rule, and Newton too would return whichever its start led to.
//
// The parallel form (central_inverse_parallel.cpp): the target centre at infinity. Then one
// target coordinate a = n · F is a 1D homography of the source, a = (k · s̃) / (g · s̃), and the
// denominator factors as (l · s̃)(g · s̃): the twist preset (x′ = u, y′ = v (1 + r u)) and any
// map that moves outputs along parallel lines, seen through affine frames. Output t's preimages
// lie on the source line (k − a g) · s̃ = 0 of the pencil through c̃_s = k × g (possibly at
// infinity, as the twist's is), parametrised projectively as s̃(μ) = p(a) + μ c̃_s; the other
// coordinate b = d · F is a ratio of quadratics on it, so b(s̃(μ)) = b_t is again a quadratic
// E(μ) = A μ² + B μ + C = 0 (A = c̃_sᵀ P c̃_s is the same for every output, 0 for the twist).
// The rule's signs again come from the root: the denominator is (l · s̃)(g · s̃), and the
// Jacobian determinant has the sign of E′(μ) · (l · s̃)(g · s̃) · det[p₀, p₁, c̃_s] · s̃_z
// (the map (a, μ) ↦ (a, b) has determinant ∂b/∂μ = E′/((l · s̃)(g · s̃)), and (a, μ) ↦ s has
// det[s̃, ∂s̃/∂a, ∂s̃/∂μ] / s̃_z³), E′ of the stable root having B's sign as above.
//
// Exactness: the roots come from the stable quadratic formula in double, so positions are
// exact to rounding (about 1e-9 px of a 6000 px frame) except within ~1e-8 of the fold, where
// the inverse itself turns with the square root of the distance (there too far below 1/256
// px); tests/core/mapping/test_central_inverse.cpp compares with Newton.
#pragma once

#include "core/mapping/inverse.h"
#include "core/mapping/rational_map.h"

#include <Eigen/Core>

#include <array>
#include <optional>

namespace artcam {

class CentralInverse {
 public:
  // The map's central form when it has one (a one-stage map whose factorisation reproduces it
  // to 1e-9 of its frame at a grid of source points), else empty. `centre` gives the signs
  // of inverse.h's pole and fold tests.
  static std::optional<CentralInverse> detect(const RationalMap& forward, FrameSize source_px,
                                              const CentreReference& centre);

  // Whether the target centre is at infinity (the parallel form above).
  bool parallel() const { return parallel_; }

  // The preimage of output point t (target pixels); false when it has none.
  bool solve(const Eigen::Vector2d& t, Eigen::Vector2d& s) const;

  // Output pixel centres (x0 + i + 0.5, y + 0.5), i < n: source positions (0 where none) and
  // valid[i]. `simd`: 0 the scalar code, 1 AVX2 lanes, 2 AVX-512 lanes, each where the CPU has
  // them (else the next lower); all give the same bits.
  void span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid, int simd) const;

  // The factors, in pixel frames (tests; the finite form's).
  const Eigen::Vector2d& centreTarget() const { return rows_.ct; }
  Eigen::Vector2d centreSource() const { return {rows_.csx, rows_.csy}; }

  // What a span needs, in pixel frames: e = E (t − c_t); α = la · e; B = m · e;
  // A = eᵀ Q₂ e; β, C; c_s; det H₂'s sign; the centre's signs.
  struct Rows {
    Eigen::Vector2d ct{0, 0};
    double e00 = 0, e01 = 0, e10 = 0, e11 = 0;
    double lax = 0, lay = 0, mx = 0, my = 0;
    double qxx = 0, qxy = 0, qyy = 0;
    double beta = 0, c = 0;
    double csx = 0, csy = 0;
    bool det_h_positive = true;
    bool den_negative = false;  // the centre's denominator
    bool det_positive = true;   // the centre's Jacobian determinant
  };

  // The parallel form's factors: unit frames on both sides as detect() makes them (source
  // s̃′ = N⁻¹ s̃, target t′ = (t − reference) / σ), the output's coordinates a = n · t′ and
  // b = d · t′, the source line's point p(a) = p₀ + a p₁ and the pencil's centre c̃_s, the
  // quadratic form P of b's numerator, and the denominator's lines l, g.
  struct ParallelRows {
    Eigen::Vector2d reference{0, 0};
    double sigma = 1.0;
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // N: unit source frame → pixels
    Eigen::Vector2d n{1, 0}, d{0, 1};
    Eigen::Vector3d p0{0, 0, 0}, p1{0, 0, 0}, cs{0, 0, 0};
    Eigen::Matrix3d along = Eigen::Matrix3d::Zero();
    Eigen::Vector3d l{0, 0, 0}, g{0, 0, 0};
    bool den_negative = false;  // the centre's denominator
    bool fold_bit = false;      // sb(B) ⊕ sb(s̃_z) a near root must have
  };

 private:
  CentralInverse() = default;
  // `unit`: the forms in unit frames, numerators less the reference's image and over σ, all
  // scaled to 1 (detect's); `frame`: N.
  static std::optional<CentralInverse> detectParallel(const RationalMap& forward, FrameSize source_px,
                                                      const CentreReference& centre,
                                                      const std::array<Eigen::Matrix3d, 3>& unit,
                                                      const Eigen::Matrix3d& frame, double sigma);
  bool solveParallel(const Eigen::Vector2d& t, Eigen::Vector2d& s) const;
  void spanParallel(int y, int x0, int n, float* sx, float* sy, unsigned char* valid, int simd) const;

  bool parallel_ = false;
  Rows rows_;
  ParallelRows parallel_rows_;
};

}  // namespace artcam
