// SPDX-License-Identifier: Apache-2.0
// Solvers in CONDITIONED coordinates (normalize.h) for a position block of n = d + 1 elements
// (d = 2 image, 3 object space). Each builds its constraint matrix and solves it; the caller
// undoes the conditioning. A null space of more than one dimension is reported, never papered
// over.
//
// Quadratic: the paper's §4. Unknowns are the upper triangles of the symmetric Q_1..Q_n with
// off-diagonal monomials doubled (eq 10): in 2D χ = (u², 2uv, 2u, v², 2v, 1), 18 unknowns; in
// 3D 40. Each match gives n - 1 rows: row i holds χ in r_i's slot and -y_i χ in r_n's. The
// tensor is the SVD null vector of that design matrix.
#pragma once

#include "core/fit/normalize.h"

#include <Eigen/Core>

#include <vector>

namespace artcam {

struct DltSolution {
  std::vector<Eigen::MatrixXd> q;  // quadratic: the n tensors
  Eigen::MatrixXd h;               // linear models: target_from_source, n×n column form
  bool linear = false;             // true: h is the model
  Eigen::VectorXd singular_values; // of the design matrix, ascending
  int null_dimension = 1;          // >1: the data do not determine the model
};

// Relative singular value below which a direction counts as null.
inline constexpr double kNullTolerance = 1e-9;
// From this many 2D matches on, the quadratic DLT solves its normal matrix instead of an SVD of
// the design matrix (O(m) sums and a fixed-size solve; exact small problems keep the SVD's
// accuracy).
inline constexpr size_t kNormalEquationsFrom = 40;
// The same for object space and colour (n = 4, 40 unknowns, 3 rows per match): the design
// matrix is 3m × 40, and its SVD (QR first) cost grows with m·40².
inline constexpr size_t kNormalEquationsFrom3d = 200;

DltSolution solveQuadraticDlt(const Points& src, const Points& dst);
// The 3D quadratic DLT's 40 × 40 normal matrix DᵀD (unknowns: the upper triangles of Q_1..Q_4,
// 10 each, in the order (0,0) (0,1) (0,2) (0,3) (1,1) (1,2) (1,3) (2,2) (2,3) (3,3)).
Eigen::MatrixXd quadraticNormal3d(const Points& src, const Points& dst);

// The 2D quadratic DLT's normal matrix DᵀD = [[A, 0, -B], [0, A, -C], [-B, -C, E]] is made of
// the 6×6 moments A = Σχχᵀ, B = ΣXχχᵀ, C = ΣYχχᵀ, E = Σ(X² + Y²)χχᵀ. Every entry of χχᵀ is a
// monomial u^i v^j (i + j ≤ 4) times a power of two, so one pass sums 15 monomials × 4 weights
// per match instead of four 6×6 outer products.
struct QuadraticMoments2d {
  Eigen::Matrix<double, 6, 6> a, b, c, e;
  // Σ mono monoᵀ for mono = (u², uv, u, v², v, 1) (χ without the doubling): the conic test.
  Eigen::Matrix<double, 6, 6> monomials;
};
// The transforms (3×3 column form, e.g. the conditioning of normalize.h) are applied to the
// points on the fly.
QuadraticMoments2d quadraticMoments2d(const Points& src, const Points& dst,
                                      const Eigen::Matrix3d& src_transform = Eigen::Matrix3d::Identity(),
                                      const Eigen::Matrix3d& dst_transform = Eigen::Matrix3d::Identity());
DltSolution solveQuadraticMoments2d(const QuadraticMoments2d& moments);
DltSolution solveProjectiveDlt(const Points& src, const Points& dst);  // homography
DltSolution solveAffine(const Points& src, const Points& dst);
DltSolution solveSimilarity(const Points& src, const Points& dst);     // 2D only
DltSolution solveTranslation(const Points& src, const Points& dst);

}  // namespace artcam
