// SPDX-License-Identifier: Apache-2.0
#include "core/colour/colour_stage.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

bool isColourCamera(const Camera& c) {
  const std::vector<Block>& b = c.blocks();
  return b.size() == 2 && b[0] == Block{BlockKind::Position, 3} &&
         b[1] == Block{BlockKind::Colour, 4} && c.stages().size() == 1;
}

}  // namespace

Camera withColourBlock(const Camera& base, const Camera& colour) {
  if (!isColourCamera(colour))
    throw std::invalid_argument("a colour block needs a one-stage [position 3 | colour 4] camera");
  const BlockLayout& old_layout = base.layout();
  const int position = old_layout.find(BlockKind::Position);
  if (position < 0 || old_layout.blocks[static_cast<size_t>(position)].size != 3)
    throw std::invalid_argument("a colour block can only join a camera with a 2D position block");

  if (base.stages().empty())
    throw std::invalid_argument("a colour block needs a camera with a stage");
  std::vector<Block> blocks = old_layout.blocks;
  const bool had_colour = old_layout.find(BlockKind::Colour) >= 0;
  if (!had_colour) blocks.insert(blocks.begin() + position + 1, Block{BlockKind::Colour, 4});
  const BlockLayout layout(blocks);
  const int n = layout.dimension;

  // Old element index → new: elements after the inserted colour block shift by 4.
  const int inserted_at = had_colour ? n : old_layout.offsets[static_cast<size_t>(position)] + 3;
  std::vector<int> from_old(static_cast<size_t>(old_layout.dimension));
  for (int k = 0; k < old_layout.dimension; ++k)
    from_old[static_cast<size_t>(k)] = k < inserted_at ? k : k + 4;
  const int colour_offset = layout.offsets[static_cast<size_t>(layout.find(BlockKind::Colour))];
  const int unit = layout.homogeneousIndex(layout.find(BlockKind::Position));
  // The colour camera's elements: position 0..2, colour 3..6.
  const int from_colour[7] = {
      layout.offsets[static_cast<size_t>(layout.find(BlockKind::Position))],
      layout.offsets[static_cast<size_t>(layout.find(BlockKind::Position))] + 1,
      unit,
      colour_offset,
      colour_offset + 1,
      colour_offset + 2,
      colour_offset + 3};

  std::vector<Stage> stages;
  const size_t last = base.stages().size() - 1;
  for (size_t s = 0; s < base.stages().size(); ++s) {
    const Stage& old_stage = base.stages()[s];
    Stage stage;
    stage.q.assign(static_cast<size_t>(n), Eigen::MatrixXd::Zero(n, n));
    for (int i = 0; i < old_layout.dimension; ++i) {
      Eigen::MatrixXd& q = stage.q[static_cast<size_t>(from_old[static_cast<size_t>(i)])];
      const Eigen::MatrixXd& old_q = old_stage.q[static_cast<size_t>(i)];
      for (int r = 0; r < old_layout.dimension; ++r)
        for (int c = 0; c < old_layout.dimension; ++c)
          q(from_old[static_cast<size_t>(r)], from_old[static_cast<size_t>(c)]) = old_q(r, c);
    }
    for (int k = 0; k < 4; ++k) {
      Eigen::MatrixXd& q = stage.q[static_cast<size_t>(colour_offset + k)];
      if (s == last) {
        q.setZero();
        const Eigen::MatrixXd& cq = colour.stages()[0].q[static_cast<size_t>(3 + k)];
        for (int r = 0; r < 7; ++r)
          for (int c = 0; c < 7; ++c) q(from_colour[r], from_colour[c]) = cq(r, c);
      } else if (!had_colour) {
        // Pass colour through an earlier stage: z_c = c · p_3 (Camera::identity's rule).
        Eigen::VectorXd e_c = Eigen::VectorXd::Zero(n), e_unit = Eigen::VectorXd::Zero(n);
        e_c[colour_offset + k] = 1.0;
        e_unit[unit] = 1.0;
        q = symmetricOuter(e_c, e_unit);
      }
    }
    stages.push_back(std::move(stage));
  }
  return Camera(std::move(blocks), std::move(stages), base.sourceSize(), base.targetSize());
}

bool applyColourCamera(const Camera& colour, const double rgb[3], double out[3]) {
  if (!isColourCamera(colour)) return false;
  Eigen::VectorXd x(7);
  x << 0.0, 0.0, 1.0, rgb[0], rgb[1], rgb[2], 1.0;
  const Eigen::VectorXd z = colour.evaluateHomogeneous(x);
  if (!(z[6] > 0.0)) return false;
  for (int k = 0; k < 3; ++k) out[k] = z[3 + k] / z[6];
  return std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2]);
}

}  // namespace artcam
