// Conditioning for the DLT (DESIGN §2, "normalise both sides"): a similarity that moves a
// point set's centroid to the origin and its RMS distance from it to √2. Building the design
// matrix from conditioned points keeps its singular values within a few orders of magnitude,
// so the SVD null space is accurate even for coordinates offset by 1e6 px.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace artcam {

// Column form: x_c = T x (homogeneous). Identity when the points are all equal.
Eigen::Matrix3d conditioningTransform(const std::vector<Eigen::Vector2d>& points);

std::vector<Eigen::Vector2d> applyTransform(const Eigen::Matrix3d& t,
                                            const std::vector<Eigen::Vector2d>& points);

// Distinct points (exact comparison after sorting).
int countDistinct(std::vector<Eigen::Vector2d> points);
// Ratio of the smaller to the larger singular value of the centred points: 0 when collinear.
double collinearity(const std::vector<Eigen::Vector2d>& points);
// Smallest singular value of the conic monomials (u², uv, v², u, v, 1) of conditioned points,
// relative to the largest: 0 when every point lies on one conic (including a line pair).
double conicDegeneracy(const std::vector<Eigen::Vector2d>& conditioned_points);

}  // namespace artcam
