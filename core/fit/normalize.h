// Conditioning for the DLT (DESIGN §2, "normalise both sides"): a similarity that moves a
// point set's centroid to the origin and its RMS distance from it to √d (d = 2 for image
// positions, 3 for object space). Building the design matrix from conditioned points keeps its
// singular values within a few orders of magnitude, so the SVD null space stays accurate even
// for coordinates offset by 1e6 px.
//
// Points are plain (non-homogeneous) vectors of d coordinates; transforms are (d+1)×(d+1),
// column form: x_c = T x.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace artcam {

using Points = std::vector<Eigen::VectorXd>;

// Identity when the points are all equal.
Eigen::MatrixXd conditioningTransform(const Points& points);
Points applyTransform(const Eigen::MatrixXd& t, const Points& points);

// Distinct points (exact comparison after sorting).
int countDistinct(Points points);
// Smallest over largest singular value of the centred points: 0 when they span fewer than d
// dimensions (collinear in 2D, coplanar in 3D).
double spreadRatio(const Points& points);
// (Both ratios are resolved to about 1e-8: compare them with thresholds of 1e-7 or more.)
// Smallest over largest singular value of the quadratic monomials of conditioned points: 0 when
// every point lies on one conic (2D) or quadric (3D), where Q_i + a_i C fits as well.
double quadricDegeneracy(const Points& conditioned_points);

}  // namespace artcam
