// SPDX-License-Identifier: Apache-2.0
#include "tests/support/straight_lines.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace artcam::test {

Eigen::Vector2d radialPhotoFromScene(double k, const Eigen::Vector2d& scene) {
  return scene * (2.0 / (1.0 + std::sqrt(1.0 + 4.0 * k * scene.squaredNorm())));
}

double bowOf(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : points) c += p;
  c /= static_cast<double>(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : points) cov += (p - c) * (p - c).transpose();
  const Eigen::Vector2d normal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvectors().col(0);
  double worst = 0;
  for (const auto& p : points) worst = std::max(worst, std::abs(normal.dot(p - c)));
  return worst;
}

}  // namespace artcam::test
