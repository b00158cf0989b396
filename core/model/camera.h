// SPDX-License-Identifier: Apache-2.0
// The ARTcam model: blocks, symmetric tensors, stages, evaluation (paper eq 3, 5).
//
// Conventions (docs/architecture.md, "The model"):
// - An input point is one ROW vector x made of blocks; each block is a homogeneous projective
//   subspace whose LAST element is its homogeneous weight: position (u, v, 1) or (X, Y, Z, 1),
//   colour premultiplied (a·r, a·g, a·b, a), depth (d, 1), and the second image's colour
//   (a·r, a·g, a·b, a) premultiplied, which compositing cameras blend with the first (eq 6/7:
//   Q_icc over both colours, the paper's generalisation of projective alpha).
// - A stage holds one symmetric N×N matrix Q_i per element (N = sum of block sizes) and maps
//   z_i = x Q_i xᵀ (eq 3). Every output block is then divided by its own homogeneous element
//   (eq 5). Output alpha is the colour block's homogeneous weight before division, clamped to
//   [0, 1].
// - A chain feeds the re-homogenised output of one stage into the next.
// - Tensors of 2D position blocks are stored in the NORMALISED frame of frames.h; the camera
//   records the source and target frame sizes in pixels.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

// SecondColour is a second image's premultiplied colour, read in the photo's frame: the input
// of compositing cameras (core/colour/composite.h). Like colour its weight is alpha, kept (and
// clamped to [0, 1]) by eq 5, not divided out to 1. Its outputs are not rendered; cameras pass
// it through unchanged so that chains keep it.
// Shading (s, 1) is a scalar no image supplies: its input is (0, 1), and a chain's earlier
// stages compute it from position so that a later stage's colour block can multiply colour by
// it (c·s is a pc-type coupling of eq 6 one stage on). That is how one camera carries a radial
// gain of higher degree than a quadratic form can, lens vignetting (core/lens/vignetting.h).
// Its outputs are not rendered.
enum class BlockKind { Position, Colour, Depth, SecondColour, Shading };

// Colour and second colour: blocks whose weight is alpha (kept by eq 5, premultiplied again
// between stages).
inline bool weightIsAlpha(BlockKind kind) {
  return kind == BlockKind::Colour || kind == BlockKind::SecondColour;
}

struct Block {
  BlockKind kind = BlockKind::Position;
  int size = 3;  // elements including the homogeneous weight (last)

  bool operator==(const Block&) const = default;
};

std::string_view blockKindName(BlockKind kind);
std::optional<BlockKind> blockKindFromName(std::string_view name);
// The element count a block of this kind must have; position may be 3 (image) or 4 (object).
bool isValidBlock(const Block& block);

// Pixel dimensions of a frame; 0×0 for frames that are not images (object space).
struct FrameSize {
  int width = 0;
  int height = 0;

  bool isImage() const { return width > 0 && height > 0; }
  bool operator==(const FrameSize&) const = default;
};

// One quadratic-form stage: z_i = x q[i] xᵀ (eq 3).
struct Stage {
  std::vector<Eigen::MatrixXd> q;
};

// Where each block lives inside x.
struct BlockLayout {
  std::vector<Block> blocks;
  std::vector<int> offsets;
  int dimension = 0;

  explicit BlockLayout(std::vector<Block> b = {});
  int find(BlockKind kind) const;  // block index or -1
  int homogeneousIndex(int block) const { return offsets[block] + blocks[block].size - 1; }
  // The element every identity/linear map multiplies by: the position block's homogeneous
  // weight if there is one, else the first block's. Multiplying by it keeps a linear map
  // linear in premultiplied colour (alpha out = alpha in).
  int unitIndex() const;
};

class Camera {
 public:
  Camera() = default;
  Camera(std::vector<Block> blocks, std::vector<Stage> stages, FrameSize source_size,
         FrameSize target_size);

  // z_i = x_i · x_unit for every element: maps every block to itself.
  static Camera identity(std::vector<Block> blocks, FrameSize source_size, FrameSize target_size);
  // A position-only camera (an RTcam) from its three normalised-frame tensors.
  static Camera rtcam(const std::vector<Eigen::Matrix3d>& q, FrameSize source_size,
                      FrameSize target_size);

  const BlockLayout& layout() const { return layout_; }
  const std::vector<Block>& blocks() const { return layout_.blocks; }
  int dimension() const { return layout_.dimension; }
  const std::vector<Stage>& stages() const { return stages_; }
  std::vector<Stage>& stages() { return stages_; }
  FrameSize sourceSize() const { return source_size_; }
  FrameSize targetSize() const { return target_size_; }
  void setFrames(FrameSize source_size, FrameSize target_size);

  // Throws std::invalid_argument naming what is wrong (sizes, symmetry, non-finite entries).
  void validate() const;
  // Replaces every Q_i by (Q_i + Q_iᵀ)/2: the same camera (eq 10).
  void symmetrize();

  // z of one stage, eq 3 (homogeneous, undivided).
  Eigen::VectorXd evaluateStage(int stage, const Eigen::VectorXd& x) const;
  // The chain's final z, undivided (stages after the first receive rehomogenise()d input).
  Eigen::VectorXd evaluateHomogeneous(const Eigen::VectorXd& x) const;
  // eq 5: every block divided by its homogeneous element, which becomes 1 (position, depth)
  // or the output alpha clamped to [0, 1] (colour). Non-finite where a weight is 0.
  Eigen::VectorXd divideBlocks(const Eigen::VectorXd& z) const;
  // The next stage's input from an undivided output: divided blocks, colour premultiplied.
  Eigen::VectorXd rehomogenise(const Eigen::VectorXd& z) const;
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x) const { return divideBlocks(evaluateHomogeneous(x)); }

 private:
  BlockLayout layout_;
  std::vector<Stage> stages_;
  FrameSize source_size_;
  FrameSize target_size_;
};

// eq 5 on raw arrays of layout.dimension elements, for hot loops that avoid Eigen's dynamic
// vectors: every block divided by its homogeneous element, which becomes 1 or the clamped
// alpha. `y` may be `z`.
void divideBlocks(const BlockLayout& layout, const double* z, double* y);

// 2D position mapping of a position-only image camera, in the normalised frame or in pixels.
// Empty where the denominator vanishes or the result is not finite.
std::optional<Eigen::Vector2d> targetFromSourceNormalized(const Camera& camera,
                                                          const Eigen::Vector2d& source);
std::optional<Eigen::Vector2d> targetPixelFromSourcePixel(const Camera& camera,
                                                          const Eigen::Vector2d& source_pixel);

// Q = (l hᵀ + h lᵀ)/2, so x Q xᵀ = (x·l)(x·h): lifts linear maps into quadratic forms.
Eigen::MatrixXd symmetricOuter(const Eigen::VectorXd& l, const Eigen::VectorXd& h);

}  // namespace artcam
