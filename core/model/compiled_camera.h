// SPDX-License-Identifier: Apache-2.0
// A camera compiled for evaluating millions of points: eq 3 as a list of non-zero terms
// z_i += q·x_a·x_b per stage (symmetric pairs merged), on fixed-size stack arrays, then eq 5
// (every block divided by its homogeneous element) exactly as Camera::divideBlocks and
// Camera::rehomogenise do. Camera::evaluate allocates per call; this does not.
#pragma once

#include "core/model/camera.h"

#include <array>
#include <vector>

namespace artcam {

class CompiledCamera {
 public:
  // The widest layout a camera may have (camera.cpp, isValidBlock): position 4, colour 4,
  // depth 2, second colour 4, shading 2.
  static constexpr int kMaxDimension = 16;
  using Vector = std::array<double, kMaxDimension>;

  CompiledCamera() = default;
  // Throws std::invalid_argument for cameras wider than kMaxDimension.
  explicit CompiledCamera(const Camera& camera);

  const BlockLayout& layout() const { return layout_; }
  int dimension() const { return layout_.dimension; }

  // The chain's final z, undivided (Camera::evaluateHomogeneous). With `position_only`, the
  // last stage computes the position block alone (the others are left 0): enough where only
  // geometry is wanted, e.g. the finite-difference steps that size splats.
  void evaluateHomogeneous(const Vector& x, Vector& z, bool position_only = false) const;
  // Every block divided by its homogeneous element (Camera::divideBlocks).
  void divide(const Vector& z, Vector& y) const;
  void evaluate(const Vector& x, Vector& y, bool position_only = false) const {
    Vector z;
    evaluateHomogeneous(x, z, position_only);
    divide(z, y);
  }
  // Every stage is the identity map (Camera::identity): evaluating it can be skipped.
  bool isIdentity() const { return identity_; }

 private:
  struct Term {
    int a, b;
    double q;
  };
  // The terms of one output, contiguous, so each output sums in a register (accumulating into
  // z[output] in memory would chain every term on a store-to-load dependency).
  struct Output {
    int index;
    bool position;  // in the position block
    std::vector<Term> terms;
  };
  void evaluateStage(size_t stage, const Vector& x, Vector& z, bool position_only) const;
  void rehomogenise(const Vector& z, Vector& x) const;

  BlockLayout layout_;
  std::vector<std::vector<Output>> stages_;
  bool identity_ = false;
};

}  // namespace artcam
