#include "core/fit/normalize.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace artcam {

Eigen::Matrix3d conditioningTransform(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(std::max<size_t>(points.size(), 1));
  double sum_sq = 0.0;
  for (const Eigen::Vector2d& p : points) sum_sq += (p - centroid).squaredNorm();
  const double rms = std::sqrt(sum_sq / static_cast<double>(std::max<size_t>(points.size(), 1)));
  const double s = rms > 0.0 ? std::sqrt(2.0) / rms : 1.0;
  Eigen::Matrix3d t;
  t << s, 0.0, -s * centroid.x(),  //
      0.0, s, -s * centroid.y(),   //
      0.0, 0.0, 1.0;
  return t;
}

std::vector<Eigen::Vector2d> applyTransform(const Eigen::Matrix3d& t,
                                            const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector3d q = t * Eigen::Vector3d(p.x(), p.y(), 1.0);
    out.push_back(q.head<2>() / q[2]);
  }
  return out;
}

int countDistinct(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  return static_cast<int>(std::unique(points.begin(), points.end()) - points.begin());
}

double collinearity(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 2) return 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix2d>(scatter).singularValues();
  return sv[0] > 0.0 ? std::sqrt(sv[1] / sv[0]) : 0.0;
}

double conicDegeneracy(const std::vector<Eigen::Vector2d>& conditioned_points) {
  if (conditioned_points.size() < 6) return 0.0;
  Eigen::MatrixXd m(conditioned_points.size(), 6);
  for (size_t r = 0; r < conditioned_points.size(); ++r) {
    const double u = conditioned_points[r].x(), v = conditioned_points[r].y();
    m.row(static_cast<Eigen::Index>(r)) << u * u, u * v, v * v, u, v, 1.0;
  }
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues();
  return sv[0] > 0.0 ? sv[5] / sv[0] : 0.0;
}

}  // namespace artcam
