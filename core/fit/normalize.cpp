#include "core/fit/normalize.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace artcam {

Eigen::MatrixXd conditioningTransform(const Points& points) {
  const Eigen::Index d = points.empty() ? 2 : points.front().size();
  Eigen::VectorXd centroid = Eigen::VectorXd::Zero(d);
  for (const Eigen::VectorXd& p : points) centroid += p;
  centroid /= static_cast<double>(std::max<size_t>(points.size(), 1));
  double sum_sq = 0.0;
  for (const Eigen::VectorXd& p : points) sum_sq += (p - centroid).squaredNorm();
  const double rms = std::sqrt(sum_sq / static_cast<double>(std::max<size_t>(points.size(), 1)));
  const double s = rms > 0.0 ? std::sqrt(static_cast<double>(d)) / rms : 1.0;
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(d + 1, d + 1);
  t.topLeftCorner(d, d) *= s;
  t.col(d).head(d) = -s * centroid;
  return t;
}

Points applyTransform(const Eigen::MatrixXd& t, const Points& points) {
  Points out;
  out.reserve(points.size());
  for (const Eigen::VectorXd& p : points) {
    const Eigen::Index d = p.size();
    const Eigen::VectorXd q = t.leftCols(d) * p + t.col(d);
    out.push_back(q.head(d) / q[d]);
  }
  return out;
}

int countDistinct(Points points) {
  std::sort(points.begin(), points.end(), [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return std::lexicographical_compare(a.data(), a.data() + a.size(), b.data(), b.data() + b.size());
  });
  return static_cast<int>(std::unique(points.begin(), points.end()) - points.begin());
}

double spreadRatio(const Points& points) {
  if (points.size() < 2) return 0.0;
  const Eigen::Index d = points.front().size();
  Eigen::VectorXd centroid = Eigen::VectorXd::Zero(d);
  for (const Eigen::VectorXd& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  // Singular values of the centred points are the square roots of the scatter matrix's
  // eigenvalues; at √eps relative resolution, enough for the 1e-7 threshold callers use.
  Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(d, d);
  for (const Eigen::VectorXd& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scatter).eigenvalues();
  return ev[d - 1] > 0.0 ? std::sqrt(std::max(ev[0], 0.0) / ev[d - 1]) : 0.0;
}

double quadricDegeneracy(const Points& conditioned_points) {
  if (conditioned_points.empty()) return 0.0;
  const Eigen::Index n = conditioned_points.front().size() + 1;
  const Eigen::Index terms = n * (n + 1) / 2;
  if (static_cast<Eigen::Index>(conditioned_points.size()) < terms) return 0.0;
  // Through the monomials' normal matrix (O(m)); √eps resolution suits the 1e-7 threshold.
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(terms, terms);
  Eigen::VectorXd x(n), mono(terms);
  for (const Eigen::VectorXd& p : conditioned_points) {
    x << p, 1.0;
    Eigen::Index c = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index k = j; k < n; ++k) mono[c++] = x[j] * x[k];
    normal.selfadjointView<Eigen::Lower>().rankUpdate(mono);
  }
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(normal, Eigen::EigenvaluesOnly).eigenvalues();
  return ev[terms - 1] > 0.0 ? std::sqrt(std::max(ev[0], 0.0) / ev[terms - 1]) : 0.0;
}

}  // namespace artcam
