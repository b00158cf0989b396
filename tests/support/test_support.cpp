// SPDX-License-Identifier: Apache-2.0
#include "tests/support/test_support.h"

#include "core/model/structure.h"

namespace artcam::test {

std::mt19937_64& rng() {
  static std::mt19937_64 generator(20261122);
  return generator;
}

double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng()); }

Camera randomRationalCamera(FrameSize source, FrameSize target, double strength) {
  Camera camera = Camera::identity({Block{BlockKind::Position, 3}}, source, target);
  for (Eigen::MatrixXd& q : camera.stages()[0].q) {
    Eigen::Matrix3d noise;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) noise(r, c) = uniform(-strength, strength);
    q += 0.5 * (noise + noise.transpose());
  }
  return camera;
}

Camera randomHomographyCamera(FrameSize source, FrameSize target) {
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) h(r, c) += uniform(-0.08, 0.08);
  Stage stage;
  for (const Eigen::MatrixXd& q : liftHomography(h)) stage.q.push_back(q);
  return Camera({Block{BlockKind::Position, 3}}, {stage}, source, target);
}

std::string resourcePath(const std::string& name) { return std::string(ARTCAM_RESOURCES_DIR) + "/" + name; }

}  // namespace artcam::test
