// SPDX-License-Identifier: Apache-2.0
#include "core/fit/normalize.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace artcam {

Eigen::MatrixXd conditioningTransform(const Points& points) {
  const Eigen::Index d = points.rows() == 0 ? 2 : points.rows();
  const Eigen::Index m = points.cols();
  const Eigen::VectorXd centroid =
      m > 0 ? Eigen::VectorXd(points.rowwise().mean()) : Eigen::VectorXd::Zero(d);
  // Two passes (centroid, then spread about it): a one-pass Σx² - m·x̄² cancels catastrophically
  // for points offset by 1e6.
  const double sum_sq = m > 0 ? (points.colwise() - centroid).squaredNorm() : 0.0;
  const double rms = std::sqrt(sum_sq / static_cast<double>(std::max<Eigen::Index>(m, 1)));
  const double s = rms > 0.0 ? std::sqrt(static_cast<double>(d)) / rms : 1.0;
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(d + 1, d + 1);
  t.topLeftCorner(d, d) *= s;
  t.col(d).head(d) = -s * centroid;
  return t;
}

Points applyTransform(const Eigen::MatrixXd& t, const Points& points) {
  const Eigen::Index d = points.rows();
  Points out = t.topLeftCorner(d, d) * points;
  out.colwise() += t.col(d).head(d);
  return out;
}

int countDistinct(const Points& points, int enough) {
  std::vector<Eigen::Index> seen;
  for (Eigen::Index k = 0; k < points.cols() && static_cast<int>(seen.size()) < enough; ++k) {
    const bool repeat = std::any_of(seen.begin(), seen.end(),
                                    [&](Eigen::Index j) { return points.col(j) == points.col(k); });
    if (!repeat) seen.push_back(k);
  }
  return static_cast<int>(seen.size());
}

double spreadRatio(const Points& points) {
  if (points.cols() < 2) return 0.0;
  const Eigen::Index d = points.rows();
  const Eigen::VectorXd centroid = points.rowwise().mean();
  // Singular values of the centred points are the square roots of the scatter matrix's
  // eigenvalues; at √eps relative resolution, enough for the 1e-7 threshold callers use.
  // Centred a chunk at a time: a centred copy of 10⁵ points cost more than the product.
  constexpr Eigen::Index kChunk = 256;
  Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(d, d);
  for (Eigen::Index b = 0; b < points.cols(); b += kChunk) {
    const Points centred = points.middleCols(b, std::min(kChunk, points.cols() - b)).colwise() - centroid;
    scatter.noalias() += centred * centred.transpose();
  }
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scatter).eigenvalues();
  return ev[d - 1] > 0.0 ? std::sqrt(std::max(ev[0], 0.0) / ev[d - 1]) : 0.0;
}

double quadricDegeneracyFromMoments(const Eigen::MatrixXd& moments) {
  const Eigen::Index terms = moments.rows();
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(moments, Eigen::EigenvaluesOnly).eigenvalues();
  return ev[terms - 1] > 0.0 ? std::sqrt(std::max(ev[0], 0.0) / ev[terms - 1]) : 0.0;
}

double quadricDegeneracy(const Points& conditioned_points) {
  if (conditioned_points.cols() == 0) return 0.0;
  const Eigen::Index n = conditioned_points.rows() + 1;
  const Eigen::Index terms = n * (n + 1) / 2;
  if (conditioned_points.cols() < terms) return 0.0;
  // Through the monomials' normal matrix (O(m)); √eps resolution suits the 1e-7 threshold.
  Eigen::MatrixXd mono(terms, conditioned_points.cols());
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < conditioned_points.cols(); ++k) {
    x << conditioned_points.col(k), 1.0;
    Eigen::Index c = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index l = j; l < n; ++l) mono(c++, k) = x[j] * x[l];
  }
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(terms, terms);
  normal.selfadjointView<Eigen::Lower>().rankUpdate(mono);
  return quadricDegeneracyFromMoments(normal);
}

}  // namespace artcam
