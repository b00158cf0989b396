// SPDX-License-Identifier: Apache-2.0
#include "core/fit/dlt.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {
namespace {

Eigen::Index dimensionOf(const Points& src) { return src.rows() == 0 ? 2 : src.rows(); }

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

// Exponents (i, j) of u^i v^j in each entry of χ = (u², 2uv, 2u, v², 2v, 1) and its factor.
constexpr int kChiU[6] = {2, 1, 1, 0, 0, 0};
constexpr int kChiV[6] = {0, 1, 0, 2, 1, 0};
constexpr double kChiFactor[6] = {1, 2, 2, 1, 2, 1};
// Index of u^i v^j (i + j ≤ 4) in the 15 monomial sums.
constexpr int monomialIndex(int i, int j) { return (i + j) * (i + j + 1) / 2 + j; }

QuadraticMoments2d quadraticMoments2d(const Points& src, const Points& dst,
                                      const Eigen::Matrix3d& src_transform,
                                      const Eigen::Matrix3d& dst_transform) {
  // Σ w·u^i v^j for the weights w = 1, X, Y, X² + Y²: a chunk of matches at a time, the
  // monomials (15 × chunk) times the weights (chunk × 4) as one small matrix product, which
  // keeps the 60 running sums out of the per-match loop.
  constexpr Eigen::Index kChunk = 128;
  Eigen::Matrix<double, 15, kChunk> mono;
  Eigen::Matrix<double, kChunk, 4> weights;
  Eigen::Matrix<double, 15, 4> sums = Eigen::Matrix<double, 15, 4>::Zero();
  const Eigen::Matrix2d sa = src_transform.topLeftCorner<2, 2>(), da = dst_transform.topLeftCorner<2, 2>();
  const Eigen::Vector2d sb = src_transform.topRightCorner<2, 1>(), db = dst_transform.topRightCorner<2, 1>();
  const Eigen::Index m = src.cols();
  for (Eigen::Index begin = 0; begin < m; begin += kChunk) {
    const Eigen::Index n = std::min(kChunk, m - begin);
    for (Eigen::Index j = 0; j < n; ++j) {
      // Conditioned on the fly (normalize.h): no conditioned copies of 10⁵ points.
      const Eigen::Vector2d p = sa * src.col(begin + j) + sb;
      const Eigen::Vector2d q = da * dst.col(begin + j) + db;
      const double u = p.x(), v = p.y(), x = q.x(), y = q.y();
      double* c = mono.col(j).data();
      c[0] = 1.0;
      for (int degree = 1; degree <= 4; ++degree) {
        const int row = degree * (degree + 1) / 2, prev = (degree - 1) * degree / 2;
        for (int l = 0; l < degree; ++l) c[row + l] = c[prev + l] * u;  // u^(d-l) v^l
        c[row + degree] = c[prev + degree - 1] * v;                    // v^d
      }
      weights.row(j) << 1.0, x, y, x * x + y * y;
    }
    sums.noalias() += mono.leftCols(n) * weights.topRows(n);
  }
  QuadraticMoments2d out;
  Eigen::Matrix<double, 6, 6>* targets[4] = {&out.a, &out.b, &out.c, &out.e};
  for (int j = 0; j < 6; ++j)
    for (int l = 0; l < 6; ++l) {
      const int idx = monomialIndex(kChiU[j] + kChiU[l], kChiV[j] + kChiV[l]);
      const double factor = kChiFactor[j] * kChiFactor[l];
      for (int a = 0; a < 4; ++a) (*targets[a])(j, l) = factor * sums(idx, a);
      out.monomials(j, l) = sums(idx, 0);
    }
  return out;
}

// The 2D quadratic DLT through its 18×18 normal matrix (see QuadraticMoments2d). O(m) with a
// small constant instead of an SVD of a 2m×18 matrix; conditioning keeps the squared condition
// number harmless at the noise levels of real data. Used for many matches only: small exact
// problems keep the SVD.
DltSolution solveQuadraticMoments2d(const QuadraticMoments2d& mo) {
  Eigen::Matrix<double, 18, 18> normal = Eigen::Matrix<double, 18, 18>::Zero();
  normal.block<6, 6>(0, 0) = mo.a;
  normal.block<6, 6>(6, 6) = mo.a;
  normal.block<6, 6>(0, 12) = -mo.b;
  normal.block<6, 6>(12, 0) = -mo.b;
  normal.block<6, 6>(6, 12) = -mo.c;
  normal.block<6, 6>(12, 6) = -mo.c;
  normal.block<6, 6>(12, 12) = mo.e;
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

// The 3D quadratic DLT through its 40×40 normal matrix: with the rows [χ in slot i, -y_i χ in
// slot 4] of each match, DᵀD has A = Σχχᵀ in slots (i, i), -B_i = -Σ y_i χχᵀ in (i, 4) and
// E = Σ|y|²χχᵀ in (4, 4); each is one product of the 10 × m monomials with its weighted copy.
Eigen::MatrixXd quadraticNormal3d(const Points& src, const Points& dst) {
  constexpr int kTerms = 10, kUnknowns = 40;
  const Eigen::Index m = src.cols();
  Eigen::Matrix<double, kTerms, Eigen::Dynamic> chi(kTerms, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const double x[4] = {src(0, k), src(1, k), src(2, k), 1.0};
    int c = 0;
    for (int j = 0; j < 4; ++j)
      for (int l = j; l < 4; ++l) chi(c++, k) = (j == l ? 1.0 : 2.0) * x[j] * x[l];
  }
  Eigen::Matrix<double, kUnknowns, kUnknowns> normal = Eigen::Matrix<double, kUnknowns, kUnknowns>::Zero();
  const Eigen::Matrix<double, kTerms, kTerms> a = chi * chi.transpose();
  for (int i = 0; i < 3; ++i) {
    normal.block<kTerms, kTerms>(kTerms * i, kTerms * i) = a;
    const Eigen::Matrix<double, kTerms, kTerms> b = chi * dst.row(i).asDiagonal() * chi.transpose();
    normal.block<kTerms, kTerms>(kTerms * i, 30) = -b;
    normal.block<kTerms, kTerms>(30, kTerms * i) = -b;
  }
  const Eigen::RowVectorXd y2 = dst.colwise().squaredNorm();
  normal.block<kTerms, kTerms>(30, 30) = chi * y2.asDiagonal() * chi.transpose();
  return normal;
}

DltSolution solveQuadraticNormal3d(const Points& src, const Points& dst) {
  constexpr int kTerms = 10, kUnknowns = 40;
  const Eigen::Matrix<double, kUnknowns, kUnknowns> normal = quadraticNormal3d(src, dst);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kUnknowns, kUnknowns>> eig(normal);
  DltSolution s;
  s.singular_values = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  // As in 2D: eigenvalues of DᵀD resolve singular values to √eps of the largest.
  const double largest = s.singular_values[kUnknowns - 1];
  s.null_dimension = 0;
  for (int i = 0; i < kUnknowns; ++i)
    if (s.singular_values[i] <= 1e-7 * largest) ++s.null_dimension;
  s.null_dimension = std::max(s.null_dimension, 1);
  const Eigen::Matrix<double, kUnknowns, 1> r = eig.eigenvectors().col(0);
  for (int i = 0; i < 4; ++i) {
    Eigen::MatrixXd q(4, 4);
    int c = kTerms * i;
    for (int j = 0; j < 4; ++j)
      for (int l = j; l < 4; ++l) q(j, l) = q(l, j) = r[c++];
    s.q.push_back(std::move(q));
  }
  return s;
}

DltSolution solveQuadraticDlt(const Points& src, const Points& dst) {
  if (dimensionOf(src) == 2 && static_cast<size_t>(src.cols()) > kNormalEquationsFrom)
    return solveQuadraticMoments2d(quadraticMoments2d(src, dst));
  if (dimensionOf(src) == 3 && static_cast<size_t>(src.cols()) > kNormalEquationsFrom3d)
    return solveQuadraticNormal3d(src, dst);
  const Eigen::Index n = dimensionOf(src) + 1;
  const Eigen::Index terms = n * (n + 1) / 2;
  const Eigen::Index m = src.cols();
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m * (n - 1), n * terms);
  Eigen::VectorXd x(n), chi(terms);
  for (Eigen::Index k = 0; k < m; ++k) {
    x << src.col(k), 1.0;
    Eigen::Index c = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index l = j; l < n; ++l) chi[c++] = (j == l ? 1.0 : 2.0) * x[j] * x[l];
    for (Eigen::Index i = 0; i < n - 1; ++i) {
      const Eigen::Index row = k * (n - 1) + i;
      d.row(row).segment(i * terms, terms) = chi.transpose();
      d.row(row).segment((n - 1) * terms, terms) = -dst(i, k) * chi.transpose();
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
  const Eigen::Index m = src.cols();
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m * (n - 1), n * n);
  Eigen::RowVectorXd x(n);
  for (Eigen::Index k = 0; k < m; ++k) {
    x << src.col(k).transpose(), 1.0;
    for (Eigen::Index i = 0; i < n - 1; ++i) {
      const Eigen::Index row = k * (n - 1) + i;
      d.row(row).segment(i * n, n) = x;
      d.row(row).segment((n - 1) * n, n) = -dst(i, k) * x;
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
  const Eigen::Index m = src.cols();
  Eigen::MatrixXd a(m, dim + 1), x;
  a.leftCols(dim) = src.transpose();
  a.col(dim).setOnes();
  const Eigen::MatrixXd b = dst.transpose();
  DltSolution s = linearLeastSquares(a, b, x);
  s.h = Eigen::MatrixXd::Identity(dim + 1, dim + 1);
  s.h.topRows(dim) = x.transpose();
  return s;
}

DltSolution solveSimilarity(const Points& src, const Points& dst) {
  if (dimensionOf(src) != 2) throw std::invalid_argument("the similarity solver is 2D only");
  const Eigen::Index m = src.cols();
  Eigen::MatrixXd a(2 * m, 4), b(2 * m, 1), x;
  for (Eigen::Index k = 0; k < m; ++k) {
    const double u = src(0, k), v = src(1, k);
    a.row(2 * k) << u, -v, 1.0, 0.0;
    a.row(2 * k + 1) << v, u, 0.0, 1.0;
    b(2 * k, 0) = dst(0, k);
    b(2 * k + 1, 0) = dst(1, k);
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
  for (Eigen::Index k = 0; k < src.cols(); ++k) t += dst.col(k) - src.col(k);
  t /= static_cast<double>(std::max<Eigen::Index>(src.cols(), 1));
  DltSolution s;
  s.linear = true;
  s.singular_values = Eigen::VectorXd::Constant(1, std::sqrt(static_cast<double>(src.cols())));
  s.h = Eigen::MatrixXd::Identity(dim + 1, dim + 1);
  s.h.col(dim).head(dim) = t;
  return s;
}

}  // namespace artcam
