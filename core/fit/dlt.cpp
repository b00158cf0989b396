#include "core/fit/dlt.h"

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

DltSolution solveQuadraticDlt(const Points& src, const Points& dst) {
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
