#include "core/fit/dlt.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {
namespace {

Eigen::Index dimensionOf(const Points& src) { return src.empty() ? 2 : src.front().size(); }

// Singular values ascending, padded with zeros to `unknowns` (a short matrix has more nulls).
Eigen::VectorXd ascendingPadded(const Eigen::VectorXd& descending, Eigen::Index unknowns) {
  Eigen::VectorXd sv = Eigen::VectorXd::Zero(unknowns);
  sv.head(descending.size()) = descending;
  return sv.reverse();
}

int nullDimension(const Eigen::VectorXd& asc) {
  const double largest = asc[asc.size() - 1];
  int n = 0;
  for (Eigen::Index i = 0; i < asc.size(); ++i)
    if (asc[i] <= kNullTolerance * largest) ++n;
  return std::max(n, 1);
}

// The null vector of the design matrix: the right singular vector of the smallest value.
DltSolution nullSpace(const Eigen::MatrixXd& design, Eigen::VectorXd& null_vector) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design, Eigen::ComputeFullV);
  DltSolution s;
  s.singular_values = ascendingPadded(svd.singularValues(), design.cols());
  s.null_dimension = nullDimension(s.singular_values);
  null_vector = svd.matrixV().col(design.cols() - 1);
  return s;
}

DltSolution linearLeastSquares(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                               Eigen::MatrixXd& x) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  DltSolution s;
  s.linear = true;
  s.singular_values = ascendingPadded(svd.singularValues(), a.cols());
  s.null_dimension = nullDimension(s.singular_values);
  x = svd.solve(b);
  return s;
}

}  // namespace

// The 2D quadratic DLT through its 18×18 normal matrix, accumulated from 6×6 blocks: with
// rows [χ, 0, -Xχ] and [0, χ, -Yχ], DᵀD = [[A, 0, -B], [0, A, -C], [-B, -C, E]] where A = Σχχᵀ,
// B = ΣXχχᵀ, C = ΣYχχᵀ, E = Σ(X² + Y²)χχᵀ. O(m) with a small constant instead of an SVD of a
// 2m×18 matrix; conditioning keeps the squared condition number harmless at the noise levels
// of real data. Used for many matches only: small exact problems keep the SVD.
DltSolution solveQuadraticNormal2d(const Points& src, const Points& dst) {
  using M6 = Eigen::Matrix<double, 6, 6>;
  M6 a = M6::Zero(), b = M6::Zero(), c = M6::Zero(), e = M6::Zero();
  Eigen::Matrix<double, 6, 1> chi;
  for (size_t k = 0; k < src.size(); ++k) {
    const double u = src[k][0], v = src[k][1], x = dst[k][0], y = dst[k][1];
    chi << u * u, 2 * u * v, 2 * u, v * v, 2 * v, 1.0;
    const M6 outer = chi * chi.transpose();
    a += outer;
    b += x * outer;
    c += y * outer;
    e += (x * x + y * y) * outer;
  }
  Eigen::Matrix<double, 18, 18> normal = Eigen::Matrix<double, 18, 18>::Zero();
  normal.block<6, 6>(0, 0) = a;
  normal.block<6, 6>(6, 6) = a;
  normal.block<6, 6>(0, 12) = -b;
  normal.block<6, 6>(12, 0) = -b;
  normal.block<6, 6>(6, 12) = -c;
  normal.block<6, 6>(12, 6) = -c;
  normal.block<6, 6>(12, 12) = e;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 18, 18>> eig(normal);
  DltSolution s;
  s.singular_values = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  // Eigenvalues of DᵀD carry absolute errors near eps·λmax, so a null direction is one whose
  // singular value is below √eps of the largest, not kNullTolerance.
  const double largest = s.singular_values[17];
  s.null_dimension = 0;
  for (int i = 0; i < 18; ++i)
    if (s.singular_values[i] <= 1e-7 * largest) ++s.null_dimension;
  s.null_dimension = std::max(s.null_dimension, 1);
  const Eigen::Matrix<double, 18, 1> r = eig.eigenvectors().col(0);
  for (int i = 0; i < 3; ++i) {
    Eigen::MatrixXd q(3, 3);
    const auto ri = r.segment<6>(6 * i);
    q << ri[0], ri[1], ri[2], ri[1], ri[3], ri[4], ri[2], ri[4], ri[5];
    s.q.push_back(std::move(q));
  }
  return s;
}

DltSolution solveQuadraticDlt(const Points& src, const Points& dst) {
  if (dimensionOf(src) == 2 && src.size() > kNormalEquationsFrom) return solveQuadraticNormal2d(src, dst);
  const Eigen::Index n = dimensionOf(src) + 1;
  const Eigen::Index terms = n * (n + 1) / 2;
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m * (n - 1), n * terms);
  Eigen::VectorXd x(n), chi(terms);
  for (Eigen::Index k = 0; k < m; ++k) {
    x << src[k], 1.0;
    Eigen::Index c = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index l = j; l < n; ++l) chi[c++] = (j == l ? 1.0 : 2.0) * x[j] * x[l];
    for (Eigen::Index i = 0; i < n - 1; ++i) {
      const Eigen::Index row = k * (n - 1) + i;
      d.row(row).segment(i * terms, terms) = chi.transpose();
      d.row(row).segment((n - 1) * terms, terms) = -dst[k][i] * chi.transpose();
    }
  }
  Eigen::VectorXd r;
  DltSolution s = nullSpace(d, r);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::MatrixXd q(n, n);
    Eigen::Index c = i * terms;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index l = j; l < n; ++l) q(j, l) = q(l, j) = r[c++];
    s.q.push_back(std::move(q));
  }
  return s;
}

DltSolution solveProjectiveDlt(const Points& src, const Points& dst) {
  const Eigen::Index n = dimensionOf(src) + 1;
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m * (n - 1), n * n);
  Eigen::RowVectorXd x(n);
  for (Eigen::Index k = 0; k < m; ++k) {
    x << src[k].transpose(), 1.0;
    for (Eigen::Index i = 0; i < n - 1; ++i) {
      const Eigen::Index row = k * (n - 1) + i;
      d.row(row).segment(i * n, n) = x;
      d.row(row).segment((n - 1) * n, n) = -dst[k][i] * x;
    }
  }
  Eigen::VectorXd h;
  DltSolution s = nullSpace(d, h);
  s.linear = true;
  s.h = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      h.data(), n, n);
  return s;
}

DltSolution solveAffine(const Points& src, const Points& dst) {
  const Eigen::Index dim = dimensionOf(src);
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd a(m, dim + 1), b(m, dim), x;
  for (Eigen::Index k = 0; k < m; ++k) {
    a.row(k) << src[k].transpose(), 1.0;
    b.row(k) = dst[k].transpose();
  }
  DltSolution s = linearLeastSquares(a, b, x);
  s.h = Eigen::MatrixXd::Identity(dim + 1, dim + 1);
  s.h.topRows(dim) = x.transpose();
  return s;
}

DltSolution solveSimilarity(const Points& src, const Points& dst) {
  if (dimensionOf(src) != 2) throw std::invalid_argument("the similarity solver is 2D only");
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd a(2 * m, 4), b(2 * m, 1), x;
  for (Eigen::Index k = 0; k < m; ++k) {
    const double u = src[k][0], v = src[k][1];
    a.row(2 * k) << u, -v, 1.0, 0.0;
    a.row(2 * k + 1) << v, u, 0.0, 1.0;
    b(2 * k, 0) = dst[k][0];
    b(2 * k + 1, 0) = dst[k][1];
  }
  DltSolution s = linearLeastSquares(a, b, x);
  s.h = Eigen::MatrixXd(3, 3);
  s.h << x(0, 0), -x(1, 0), x(2, 0),  //
      x(1, 0), x(0, 0), x(3, 0),      //
      0.0, 0.0, 1.0;
  return s;
}

DltSolution solveTranslation(const Points& src, const Points& dst) {
  const Eigen::Index dim = dimensionOf(src);
  Eigen::VectorXd t = Eigen::VectorXd::Zero(dim);
  for (size_t k = 0; k < src.size(); ++k) t += dst[k] - src[k];
  t /= static_cast<double>(std::max<size_t>(src.size(), 1));
  DltSolution s;
  s.linear = true;
  s.singular_values = Eigen::VectorXd::Constant(1, std::sqrt(static_cast<double>(src.size())));
  s.h = Eigen::MatrixXd::Identity(dim + 1, dim + 1);
  s.h.col(dim).head(dim) = t;
  return s;
}

}  // namespace artcam
