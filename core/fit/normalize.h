// SPDX-License-Identifier: Apache-2.0
// Conditioning for the DLT, on both sides of the matches: a similarity that moves a
// point set's centroid to the origin and its RMS distance from it to √d (d = 2 for image
// positions, 3 for object space or colour). Building the design matrix from conditioned points
// keeps its singular values within a few orders of magnitude, so the SVD null space stays
// accurate even for coordinates offset by 1e6 px.
//
// Points are stored d × m, one plain (non-homogeneous) point per COLUMN: one contiguous
// allocation however many matches there are (a vector of per-point VectorXd cost an allocation
// per point and dominated fits of 100 000 matches). Transforms are (d+1)×(d+1), column form:
// x_c = T x.
#pragma once

#include <Eigen/Core>

namespace artcam {

// d × m, one point per column.
using Points = Eigen::MatrixXd;

// Identity when the points are all equal.
Eigen::MatrixXd conditioningTransform(const Points& points);
// T must be a similarity or affine map (last row (0, …, 0, 1)), as conditioning transforms are.
Points applyTransform(const Eigen::MatrixXd& t, const Points& points);

// Distinct points (exact comparison), counted up to `enough`: the answer is exact when it is
// below `enough` and `enough` otherwise. O(m · enough), and it stops as soon as `enough`
// distinct points are seen, which for real data is within the first few.
int countDistinct(const Points& points, int enough);
// Smallest over largest singular value of the centred points: 0 when they span fewer than d
// dimensions (collinear in 2D, coplanar in 3D).
double spreadRatio(const Points& points);
// (Both ratios are resolved to about 1e-8: compare them with thresholds of 1e-7 or more.)
// Smallest over largest singular value of the quadratic monomials of conditioned points: 0 when
// every point lies on one conic (2D) or quadric (3D), where Q_i + a_i C fits as well.
double quadricDegeneracy(const Points& conditioned_points);
// The same figure from the monomial moment matrix Σ mono monoᵀ (mono = x_j x_k, j ≤ k, of the
// homogeneous point), for callers that accumulate it anyway.
double quadricDegeneracyFromMoments(const Eigen::MatrixXd& moments);

}  // namespace artcam
