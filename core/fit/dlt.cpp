#include "core/fit/dlt.h"

#include "core/model/camera.h"

#include <Eigen/QR>
#include <Eigen/SVD>

namespace artcam {
namespace {

Eigen::VectorXd ascending(const Eigen::VectorXd& descending) { return descending.reverse(); }

int nullDimension(const Eigen::VectorXd& asc) {
  const double largest = asc[asc.size() - 1];
  int n = 0;
  for (Eigen::Index i = 0; i < asc.size(); ++i)
    if (asc[i] <= kNullTolerance * largest) ++n;
  return std::max(n, 1);
}

void liftLinear(DltSolution& s) {
  s.linear = true;
  const Eigen::Vector3d infinity(0, 0, 1);
  for (int i = 0; i < 3; ++i) s.q[i] = symmetricOuter(infinity, s.h.row(i).transpose());
}

}  // namespace

DltSolution solveQuadraticDlt(const std::vector<Eigen::Vector2d>& src,
                              const std::vector<Eigen::Vector2d>& dst) {
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(2 * m, 18);
  for (Eigen::Index k = 0; k < m; ++k) {
    const double u = src[k].x(), v = src[k].y();
    Eigen::Matrix<double, 1, 6> chi;
    chi << u * u, 2 * u * v, 2 * u, v * v, 2 * v, 1.0;  // upper triangle, off-diagonals doubled
    d.block<1, 6>(2 * k, 0) = chi;
    d.block<1, 6>(2 * k, 12) = -dst[k].x() * chi;
    d.block<1, 6>(2 * k + 1, 6) = chi;
    d.block<1, 6>(2 * k + 1, 12) = -dst[k].y() * chi;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(d, Eigen::ComputeFullV);
  DltSolution s;
  Eigen::VectorXd sv = Eigen::VectorXd::Zero(18);
  sv.head(svd.singularValues().size()) = svd.singularValues();
  s.singular_values = ascending(sv);
  s.null_dimension = nullDimension(s.singular_values);
  const Eigen::VectorXd r = svd.matrixV().col(17);
  for (int i = 0; i < 3; ++i) {
    const auto ri = r.segment<6>(6 * i);
    s.q[i] << ri[0], ri[1], ri[2],  //
        ri[1], ri[3], ri[4],        //
        ri[2], ri[4], ri[5];
  }
  return s;
}

DltSolution solveHomographyDlt(const std::vector<Eigen::Vector2d>& src,
                               const std::vector<Eigen::Vector2d>& dst) {
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(2 * m, 9);
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::RowVector3d x(src[k].x(), src[k].y(), 1.0);
    d.block<1, 3>(2 * k, 0) = x;
    d.block<1, 3>(2 * k, 6) = -dst[k].x() * x;
    d.block<1, 3>(2 * k + 1, 3) = x;
    d.block<1, 3>(2 * k + 1, 6) = -dst[k].y() * x;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(d, Eigen::ComputeFullV);
  DltSolution s;
  Eigen::VectorXd sv = Eigen::VectorXd::Zero(9);
  sv.head(svd.singularValues().size()) = svd.singularValues();
  s.singular_values = ascending(sv);
  s.null_dimension = nullDimension(s.singular_values);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  s.h << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  liftLinear(s);
  return s;
}

DltSolution solveAffine(const std::vector<Eigen::Vector2d>& src,
                        const std::vector<Eigen::Vector2d>& dst) {
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd a(m, 3);
  Eigen::MatrixXd b(m, 2);
  for (Eigen::Index k = 0; k < m; ++k) {
    a.row(k) << src[k].x(), src[k].y(), 1.0;
    b.row(k) << dst[k].x(), dst[k].y();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  DltSolution s;
  s.singular_values = ascending(svd.singularValues());
  s.null_dimension = s.singular_values[0] <= kNullTolerance * s.singular_values[2] ? 2 : 1;
  const Eigen::MatrixXd x = svd.solve(b);  // 3×2
  s.h.setIdentity();
  s.h.topRows<2>() = x.transpose();
  liftLinear(s);
  return s;
}

DltSolution solveSimilarity(const std::vector<Eigen::Vector2d>& src,
                            const std::vector<Eigen::Vector2d>& dst) {
  const Eigen::Index m = static_cast<Eigen::Index>(src.size());
  Eigen::MatrixXd a(2 * m, 4);
  Eigen::VectorXd b(2 * m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const double u = src[k].x(), v = src[k].y();
    a.row(2 * k) << u, -v, 1.0, 0.0;
    a.row(2 * k + 1) << v, u, 0.0, 1.0;
    b[2 * k] = dst[k].x();
    b[2 * k + 1] = dst[k].y();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  DltSolution s;
  s.singular_values = ascending(svd.singularValues());
  s.null_dimension = s.singular_values[0] <= kNullTolerance * s.singular_values[3] ? 2 : 1;
  const Eigen::Vector4d x = svd.solve(b);
  s.h << x[0], -x[1], x[2],  //
      x[1], x[0], x[3],      //
      0.0, 0.0, 1.0;
  liftLinear(s);
  return s;
}

DltSolution solveTranslation(const std::vector<Eigen::Vector2d>& src,
                             const std::vector<Eigen::Vector2d>& dst) {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < src.size(); ++k) t += dst[k] - src[k];
  t /= static_cast<double>(std::max<size_t>(src.size(), 1));
  DltSolution s;
  s.singular_values = Eigen::VectorXd::Constant(1, std::sqrt(static_cast<double>(src.size())));
  s.h.setIdentity();
  s.h.col(2).head<2>() = t;
  liftLinear(s);
  return s;
}

}  // namespace artcam
