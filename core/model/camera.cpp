// SPDX-License-Identifier: Apache-2.0
#include "core/model/camera.h"

#include "core/model/frames.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace artcam {

std::string_view blockKindName(BlockKind kind) {
  switch (kind) {
    case BlockKind::Position: return "position";
    case BlockKind::Colour: return "colour";
    case BlockKind::Depth: return "depth";
    case BlockKind::SecondColour: return "second-colour";
    case BlockKind::Shading:
      return "shading";
  }
  return "unknown";
}

std::optional<BlockKind> blockKindFromName(std::string_view name) {
  if (name == "position") return BlockKind::Position;
  if (name == "colour" || name == "color") return BlockKind::Colour;
  if (name == "depth") return BlockKind::Depth;
  if (name == "second-colour" || name == "second-color") return BlockKind::SecondColour;
  if (name == "shading") return BlockKind::Shading;
  return std::nullopt;
}

bool isValidBlock(const Block& block) {
  switch (block.kind) {
    case BlockKind::Position: return block.size == 3 || block.size == 4;
    case BlockKind::Colour: return block.size == 4;
    case BlockKind::Depth: return block.size == 2;
    case BlockKind::SecondColour: return block.size == 4;
    case BlockKind::Shading:
      return block.size == 2;
  }
  return false;
}

BlockLayout::BlockLayout(std::vector<Block> b) : blocks(std::move(b)) {
  offsets.reserve(blocks.size());
  for (const Block& block : blocks) {
    offsets.push_back(dimension);
    dimension += block.size;
  }
}

int BlockLayout::find(BlockKind kind) const {
  for (size_t b = 0; b < blocks.size(); ++b)
    if (blocks[b].kind == kind) return static_cast<int>(b);
  return -1;
}

int BlockLayout::unitIndex() const {
  const int position = find(BlockKind::Position);
  return homogeneousIndex(position >= 0 ? position : 0);
}

Camera::Camera(std::vector<Block> blocks, std::vector<Stage> stages, FrameSize source_size,
               FrameSize target_size)
    : layout_(std::move(blocks)),
      stages_(std::move(stages)),
      source_size_(source_size),
      target_size_(target_size) {
  validate();
}

Camera Camera::identity(std::vector<Block> blocks, FrameSize source_size, FrameSize target_size) {
  const BlockLayout layout(blocks);
  const int n = layout.dimension;
  Stage stage;
  for (int i = 0; i < n; ++i) {
    stage.q.push_back(symmetricOuter(Eigen::VectorXd::Unit(n, i),
                                     Eigen::VectorXd::Unit(n, layout.unitIndex())));
  }
  return Camera(std::move(blocks), {std::move(stage)}, source_size, target_size);
}

Camera Camera::rtcam(const std::vector<Eigen::Matrix3d>& q, FrameSize source_size,
                     FrameSize target_size) {
  if (q.size() != 3) throw std::invalid_argument("an image RTcam needs exactly 3 tensors");
  Stage stage;
  for (const Eigen::Matrix3d& m : q) stage.q.emplace_back(m);
  return Camera({Block{BlockKind::Position, 3}}, {std::move(stage)}, source_size, target_size);
}

void Camera::setFrames(FrameSize source_size, FrameSize target_size) {
  source_size_ = source_size;
  target_size_ = target_size;
}

void Camera::validate() const {
  if (layout_.blocks.empty()) throw std::invalid_argument("camera has no blocks");
  for (size_t b = 0; b < layout_.blocks.size(); ++b) {
    const Block& block = layout_.blocks[b];
    if (!isValidBlock(block))
      throw std::invalid_argument("block " + std::to_string(b) + " (" +
                                  std::string(blockKindName(block.kind)) + ") has " +
                                  std::to_string(block.size) + " elements, which that kind does not allow");
    for (size_t c = 0; c < b; ++c)
      if (layout_.blocks[c].kind == block.kind)
        throw std::invalid_argument("block kind " + std::string(blockKindName(block.kind)) +
                                    " appears twice");
  }
  // The second image's colour is what a compositing camera blends into the first: alone it
  // has nothing to blend with.
  if (layout_.find(BlockKind::SecondColour) >= 0 && layout_.find(BlockKind::Colour) < 0)
    throw std::invalid_argument("a second-colour block needs a colour block");
  if (stages_.empty()) throw std::invalid_argument("camera has no stages");
  const int n = layout_.dimension;
  for (size_t s = 0; s < stages_.size(); ++s) {
    const Stage& stage = stages_[s];
    if (static_cast<int>(stage.q.size()) != n)
      throw std::invalid_argument("stage " + std::to_string(s) + " has " +
                                  std::to_string(stage.q.size()) + " tensors, expected " +
                                  std::to_string(n));
    for (int i = 0; i < n; ++i) {
      const Eigen::MatrixXd& m = stage.q[i];
      const std::string where = "stage " + std::to_string(s) + " tensor " + std::to_string(i);
      if (m.rows() != n || m.cols() != n)
        throw std::invalid_argument(where + " is " + std::to_string(m.rows()) + "x" +
                                    std::to_string(m.cols()) + ", expected " + std::to_string(n) +
                                    "x" + std::to_string(n));
      if (!m.allFinite()) throw std::invalid_argument(where + " has a non-finite entry");
    }
  }
  const bool has_image_position = [&] {
    const int p = layout_.find(BlockKind::Position);
    return p >= 0 && layout_.blocks[p].size == 3;
  }();
  if (has_image_position && (!source_size_.isImage() || !target_size_.isImage()))
    throw std::invalid_argument("an image camera needs positive source and target frame sizes");
}

void Camera::symmetrize() {
  for (Stage& stage : stages_)
    for (Eigen::MatrixXd& m : stage.q) m = (0.5 * (m + m.transpose())).eval();
}

Eigen::VectorXd Camera::evaluateStage(int stage, const Eigen::VectorXd& x) const {
  const Stage& st = stages_.at(stage);
  const int n = layout_.dimension;
  Eigen::VectorXd z(n);
  for (int i = 0; i < n; ++i) z[i] = x.dot(st.q[i] * x);  // eq 3
  return z;
}

Eigen::VectorXd Camera::evaluateHomogeneous(const Eigen::VectorXd& x) const {
  Eigen::VectorXd z = evaluateStage(0, x);
  for (int s = 1; s < static_cast<int>(stages_.size()); ++s) z = evaluateStage(s, rehomogenise(z));
  return z;
}

void divideBlocks(const BlockLayout& layout, const double* z, double* y) {
  for (size_t b = 0; b < layout.blocks.size(); ++b) {
    const int off = layout.offsets[b];
    const int h = layout.homogeneousIndex(static_cast<int>(b));
    const double w = z[h];
    for (int k = off; k < h; ++k) y[k] = z[k] / w;  // eq 5
    y[h] = weightIsAlpha(layout.blocks[b].kind) ? std::clamp(w, 0.0, 1.0) : 1.0;
  }
}

Eigen::VectorXd Camera::divideBlocks(const Eigen::VectorXd& z) const {
  Eigen::VectorXd y(z.size());
  artcam::divideBlocks(layout_, z.data(), y.data());
  return y;
}

Eigen::VectorXd Camera::rehomogenise(const Eigen::VectorXd& z) const {
  Eigen::VectorXd x = divideBlocks(z);
  for (size_t b = 0; b < layout_.blocks.size(); ++b) {
    if (!weightIsAlpha(layout_.blocks[b].kind)) continue;
    const int off = layout_.offsets[b];
    const int h = layout_.homogeneousIndex(static_cast<int>(b));
    for (int k = off; k < h; ++k) x[k] *= x[h];  // back to premultiplied colour
  }
  return x;
}

std::optional<Eigen::Vector2d> targetFromSourceNormalized(const Camera& camera,
                                                          const Eigen::Vector2d& source) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[p].size != 3 || layout.blocks.size() != 1)
    throw std::invalid_argument("2D point mapping needs a position-only image camera");
  Eigen::VectorXd x = Eigen::Vector3d(source.x(), source.y(), 1.0);
  const int last = static_cast<int>(camera.stages().size()) - 1;
  for (int s = 0; s < last; ++s) x = camera.rehomogenise(camera.evaluateStage(s, x));
  const Eigen::VectorXd z = camera.evaluateStage(last, x);
  // On the pole curve the denominator is zero only in exact arithmetic: computed, it is
  // rounding noise (1e-18 on a pole circle), and z/w a point 1e17 px away. A denominator within
  // the rounding bound of the last stage's quadratic form (eq 3: |xᵀQx| error ≤ n·ε·|x|ᵀ|Q||x|)
  // is taken as the pole: no image.
  const Eigen::VectorXd ax = x.cwiseAbs();
  const double w_bound = 8.0 * std::numeric_limits<double>::epsilon() *
                         ax.dot(camera.stages()[last].q[2].cwiseAbs() * ax);
  if (!(std::abs(z[2]) > w_bound)) return std::nullopt;
  const Eigen::Vector2d y(z[0] / z[2], z[1] / z[2]);
  if (!y.allFinite()) return std::nullopt;
  return y;
}

std::optional<Eigen::Vector2d> targetPixelFromSourcePixel(const Camera& camera,
                                                          const Eigen::Vector2d& source_pixel) {
  const auto y = targetFromSourceNormalized(
      camera, normalizedFromPixel(camera.sourceSize(), source_pixel));
  if (!y) return std::nullopt;
  return pixelFromNormalized(camera.targetSize(), *y);
}

Eigen::MatrixXd symmetricOuter(const Eigen::VectorXd& l, const Eigen::VectorXd& h) {
  return 0.5 * (l * h.transpose() + h * l.transpose());
}

}  // namespace artcam
