// SPDX-License-Identifier: Apache-2.0
#include "core/model/frames.h"

#include <algorithm>
#include <stdexcept>

namespace artcam {
namespace {

double frameScale(FrameSize frame) {
  if (!frame.isImage()) throw std::invalid_argument("frame has no image size");
  return std::max(frame.width, frame.height) / 2.0;
}

}  // namespace

Eigen::Vector2d normalizedFromPixel(FrameSize frame, const Eigen::Vector2d& pixel) {
  const double s = frameScale(frame);
  return {(pixel.x() - frame.width / 2.0) / s, (pixel.y() - frame.height / 2.0) / s};
}

Eigen::Vector2d pixelFromNormalized(FrameSize frame, const Eigen::Vector2d& normalized) {
  const double s = frameScale(frame);
  return {normalized.x() * s + frame.width / 2.0, normalized.y() * s + frame.height / 2.0};
}

Eigen::Matrix3d normalizedFromPixelMatrix(FrameSize frame) {
  const double s = frameScale(frame);
  Eigen::Matrix3d m;
  m << 1.0 / s, 0.0, -frame.width / (2.0 * s),  //
      0.0, 1.0 / s, -frame.height / (2.0 * s),  //
      0.0, 0.0, 1.0;
  return m;
}

Eigen::Matrix3d pixelFromNormalizedMatrix(FrameSize frame) {
  const double s = frameScale(frame);
  Eigen::Matrix3d m;
  m << s, 0.0, frame.width / 2.0,  //
      0.0, s, frame.height / 2.0,  //
      0.0, 0.0, 1.0;
  return m;
}

void changeInputFrame(Camera& camera, int block, const Eigen::MatrixXd& h_row) {
  const BlockLayout& layout = camera.layout();
  const int k = layout.blocks.at(block).size;
  if (h_row.rows() != k || h_row.cols() != k)
    throw std::invalid_argument("input frame change has the wrong size for its block");
  const int n = layout.dimension;
  Eigen::MatrixXd h = Eigen::MatrixXd::Identity(n, n);
  h.block(layout.offsets[block], layout.offsets[block], k, k) = h_row;
  for (Eigen::MatrixXd& q : camera.stages().front().q) q = (h * q * h.transpose()).eval();
}

void changeOutputFrame(Camera& camera, int block, const Eigen::MatrixXd& a_col) {
  const BlockLayout& layout = camera.layout();
  const int k = layout.blocks.at(block).size;
  if (a_col.rows() != k || a_col.cols() != k)
    throw std::invalid_argument("output frame change has the wrong size for its block");
  const int off = layout.offsets[block];
  std::vector<Eigen::MatrixXd>& q = camera.stages().back().q;
  std::vector<Eigen::MatrixXd> mixed(k, Eigen::MatrixXd::Zero(layout.dimension, layout.dimension));
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) mixed[i] += a_col(i, j) * q[off + j];
  for (int i = 0; i < k; ++i) q[off + i] = std::move(mixed[i]);
}

void reframeToRegions(Camera& camera, double source_x, double source_y, FrameSize source_size,
                      double target_x, double target_y, FrameSize target_size) {
  const int position = camera.layout().find(BlockKind::Position);
  if (position >= 0 && camera.layout().blocks[static_cast<size_t>(position)].size == 3) {
    const auto shift = [](double x, double y) {
      Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
      t(0, 2) = x;
      t(1, 2) = y;
      return t;
    };
    // region-normalised → region pixels → frame pixels → frame-normalised, for column vectors.
    const Eigen::Matrix3d frame_from_source = normalizedFromPixelMatrix(camera.sourceSize()) *
                                              shift(source_x, source_y) *
                                              pixelFromNormalizedMatrix(source_size);
    const Eigen::Matrix3d target_from_frame = normalizedFromPixelMatrix(target_size) *
                                              shift(-target_x, -target_y) *
                                              pixelFromNormalizedMatrix(camera.targetSize());
    changeInputFrame(camera, position, frame_from_source.transpose());
    changeOutputFrame(camera, position, target_from_frame);
  }
  camera.setFrames(source_size, target_size);
}

std::vector<Eigen::Matrix3d> positionTensorsInPixels(const Camera& camera) {
  const BlockLayout& layout = camera.layout();
  if (layout.blocks.size() != 1 || layout.blocks[0].kind != BlockKind::Position ||
      layout.blocks[0].size != 3 || camera.stages().size() != 1)
    throw std::invalid_argument("pixel tensors need a single-stage 2D position camera");
  Camera c = camera;
  // x_n(row) = x_p(row) * N_colᵀ, so H_row = N_colᵀ.
  changeInputFrame(c, 0, normalizedFromPixelMatrix(camera.sourceSize()).transpose());
  changeOutputFrame(c, 0, pixelFromNormalizedMatrix(camera.targetSize()));
  std::vector<Eigen::Matrix3d> out;
  for (const Eigen::MatrixXd& q : c.stages()[0].q) out.emplace_back(q);
  return out;
}

}  // namespace artcam
