// SPDX-License-Identifier: Apache-2.0
// Composition of cameras; see compose.h for the three outcomes and why.
#include "core/model/compose.h"

#include "core/model/frames.h"
#include "core/model/structure.h"

#include <Eigen/Dense>

#include <cmath>
#include <utility>

namespace artcam {
namespace {

bool isPositionOnly(const Camera& camera) {
  return camera.blocks().size() == 1 && camera.blocks()[0].kind == BlockKind::Position;
}

// A single-stage position-only camera whose geometry is at most a homography: its column-form
// target_from_source matrix in the normalised frames.
std::optional<Eigen::MatrixXd> homographyOf(const Camera& camera) {
  if (!isPositionOnly(camera) || camera.stages().size() != 1) return std::nullopt;
  const CameraStructure s = analyseStructure(camera);
  if (s.degenerate || s.geometry == GeometryClass::Rational || s.homography.size() == 0)
    return std::nullopt;
  return s.homography;
}

// Column-form map from first's target normalised frame to second's source normalised frame
// through pixels; the identity for equal sizes and for object space.
Eigen::MatrixXd frameBridge(const Camera& first, const Camera& second) {
  const int k = first.blocks()[static_cast<size_t>(first.layout().find(BlockKind::Position))].size;
  if (k != 3 || first.targetSize() == second.sourceSize() || !first.targetSize().isImage())
    return Eigen::MatrixXd::Identity(k, k);
  return normalizedFromPixelMatrix(second.sourceSize()) *
         pixelFromNormalizedMatrix(first.targetSize());
}

// Position-only tensors are defined up to one common scale; keep entries near 1 so chained
// homographies do not drift towards overflow. (With colour blocks the scale is alpha, so
// those cameras are left as they are.)
void rescalePositionOnly(Camera& camera) {
  if (!isPositionOnly(camera)) return;
  for (Stage& stage : camera.stages()) {
    double largest = 0.0;
    for (const Eigen::MatrixXd& q : stage.q) largest = std::max(largest, q.cwiseAbs().maxCoeff());
    if (largest > 0.0 && std::isfinite(largest))
      for (Eigen::MatrixXd& q : stage.q) q /= largest;
  }
}

}  // namespace

Result<Camera> composeCameras(const Camera& first, const Camera& second,
                              CompositionSummary* summary) {
  if (first.blocks() != second.blocks())
    return Result<Camera>::failure(
        "the two cameras have different blocks; compose needs the same blocks on both");
  const int position = first.layout().find(BlockKind::Position);
  if (position < 0)
    return Result<Camera>::failure("compose needs cameras with a position block");
  if (first.targetSize().isImage() != second.sourceSize().isImage())
    return Result<Camera>::failure(
        "the first camera's target frame (" + std::to_string(first.targetSize().width) + "x" +
        std::to_string(first.targetSize().height) + ") and the second's source frame (" +
        std::to_string(second.sourceSize().width) + "x" +
        std::to_string(second.sourceSize().height) +
        ") are not both images or both object space");

  const Eigen::MatrixXd bridge = frameBridge(first, second);
  CompositionSummary local;
  Camera out;

  if (const auto a = homographyOf(second)) {
    // Output side: second's homography after the bridge mixes first's outputs.
    out = first;
    changeOutputFrame(out, position, (*a) * bridge);
    local.kind = CompositionKind::OutputHomography;
    local.description = "the second camera is a homography: folded into the first's outputs";
  } else if (const auto h = homographyOf(first)) {
    // Input side: x2 = (bridge · H) x1 in column form, so x2_row = x1_row (bridge · H)ᵀ.
    // homographyOf() admits position-only cameras, and the blocks match, so every output of
    // second is a form in position alone and H's change of homogeneous weight cancels (eq 5).
    out = second;
    changeInputFrame(out, position, (bridge * (*h)).transpose());
    local.kind = CompositionKind::InputHomography;
    local.description = "the first camera is a homography: folded into the second's inputs";
  } else {
    Camera tail = second;
    if (!bridge.isIdentity(0.0)) changeInputFrame(tail, position, bridge.transpose());
    std::vector<Stage> stages = first.stages();
    for (const Stage& s : tail.stages()) stages.push_back(s);
    out = Camera(first.blocks(), std::move(stages), first.sourceSize(), second.targetSize());
    local.kind = CompositionKind::Chain;
    local.description = "general cameras: a chain of " + std::to_string(out.stages().size()) +
                        " stages (first's, then second's)";
  }
  out.setFrames(first.sourceSize(), second.targetSize());
  rescalePositionOnly(out);
  out.validate();
  local.stages = static_cast<int>(out.stages().size());
  if (summary) *summary = std::move(local);
  return Result<Camera>::success(std::move(out));
}

}  // namespace artcam

namespace artcam {
namespace {

// Evaluates `camera` at the source frame centre with a mid-grey opaque colour and depth d.
Eigen::VectorXd probe(const Camera& camera, double d) {
  const BlockLayout& layout = camera.layout();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.dimension);
  for (size_t b = 0; b < layout.blocks.size(); ++b) {
    const int o = layout.offsets[b];
    const Block& block = layout.blocks[b];
    if (block.kind == BlockKind::Position) {
      x(o + block.size - 1) = 1.0;
      for (int k = 0; k + 1 < block.size; ++k) x(o + k) = 0.1 * (k + 1);
    } else if (block.kind == BlockKind::Colour) {
      for (int k = 0; k + 1 < block.size; ++k) x(o + k) = 0.5;
      x(o + block.size - 1) = 1.0;
    } else {
      x(o) = d;
      x(o + 1) = 1.0;
    }
  }
  return camera.evaluate(x);
}

const double kProbeDepths[] = {0.7, 2.0, 9.0, 40.0};

// The depth output differs from the depth input.
bool changesDepth(const Camera& camera) {
  const int b = camera.layout().find(BlockKind::Depth);
  if (b < 0) return false;
  const int o = camera.layout().offsets[static_cast<size_t>(b)];
  for (const double d : kProbeDepths) {
    const Eigen::VectorXd y = probe(camera, d);
    if (!(std::abs(y(o) - d) <= 1e-9 * std::max(1.0, d))) return true;
  }
  return false;
}

// Some output depends on the depth input (beyond passing it on unchanged).
bool readsDepth(const Camera& camera) {
  if (camera.layout().find(BlockKind::Depth) < 0) return false;
  if (changesDepth(camera)) return true;
  const int b = camera.layout().find(BlockKind::Depth);
  const int o = camera.layout().offsets[static_cast<size_t>(b)];
  const Eigen::VectorXd reference = probe(camera, kProbeDepths[0]);
  for (const double d : kProbeDepths) {
    Eigen::VectorXd y = probe(camera, d);
    y(o) = reference(o);
    if (!((y - reference).cwiseAbs().maxCoeff() <= 1e-9)) return true;
  }
  return false;
}

// A position-only camera written over `blocks`: its position tensors embedded at the position
// block, every other element passed on (x_i · x_unit, as Camera::identity does).
Camera liftToBlocks(const Camera& camera, const std::vector<Block>& blocks) {
  const BlockLayout layout(blocks);
  const int p = layout.offsets[static_cast<size_t>(layout.find(BlockKind::Position))];
  const int k = camera.dimension();
  std::vector<Stage> stages;
  for (const Stage& stage : camera.stages()) {
    Stage lifted;
    for (int i = 0; i < layout.dimension; ++i) {
      if (i >= p && i < p + k) {
        Eigen::MatrixXd q = Eigen::MatrixXd::Zero(layout.dimension, layout.dimension);
        q.block(p, p, k, k) = stage.q[static_cast<size_t>(i - p)];
        lifted.q.push_back(std::move(q));
      } else {
        lifted.q.push_back(symmetricOuter(Eigen::VectorXd::Unit(layout.dimension, i),
                                          Eigen::VectorXd::Unit(layout.dimension, layout.unitIndex())));
      }
    }
    stages.push_back(std::move(lifted));
  }
  return Camera(blocks, std::move(stages), camera.sourceSize(), camera.targetSize());
}

bool positionOnly(const Camera& c) {
  return c.blocks().size() == 1 && c.blocks()[0].kind == BlockKind::Position;
}

// Brings a position-only side to the other side's blocks, so a lens composes with a camera
// that carries colour or depth.
std::pair<Camera, Camera> commonBlocks(const Camera& a, const Camera& b) {
  if (a.blocks() == b.blocks()) return {a, b};
  const int pa = a.layout().find(BlockKind::Position), pb = b.layout().find(BlockKind::Position);
  if (pa < 0 || pb < 0 || a.blocks()[size_t(pa)] != b.blocks()[size_t(pb)]) return {a, b};
  if (positionOnly(a)) return {liftToBlocks(a, b.blocks()), b};
  if (positionOnly(b)) return {a, liftToBlocks(b, a.blocks())};
  return {a, b};
}

bool positionOnlyImage(const Artcam& c) {
  return c.layers.size() == 1 && !c.pieces && c.blocks().size() == 1 &&
         c.blocks()[0].kind == BlockKind::Position && c.blocks()[0].size == 3 &&
         c.depth_output == DepthOutput::Depth;
}

}  // namespace

Result<Artcam> composeArtcams(const Artcam& first, const Artcam& second, std::string* description) {
  using R = Result<Artcam>;
  if (second.pieces)
    return R::failure("a piecewise camera can only come first (its patches are rectangles of its "
                      "own source, which the first camera would bend)");
  if (first.pieces && !positionOnlyImage(second))
    return R::failure("a piecewise camera composes only with a single position-only image camera");
  if (first.depth_output == DepthOutput::BlurVariance)
    return R::failure("the first camera's depth output is a blur variance (depth of field), not a "
                      "depth: depth of field must come last");
  const size_t n1 = first.layers.size(), n2 = second.layers.size();
  if (n1 > 1 && n2 > 1 && n1 != n2)
    return R::failure("layered cameras compose layer by layer and need as many layers (" +
                      std::to_string(n1) + " and " + std::to_string(n2) + ")");
  for (const Camera& a : first.layers)
    for (const Camera& b : second.layers)
      if (changesDepth(a) && readsDepth(b))
        return R::failure("the first camera outputs something else than the depth it read (e.g. "
                          "aerial perspective's log depth) and the second reads depth: composed, "
                          "it would read the wrong quantity");
  Artcam out;
  out.depth_output = second.depth_output;
  std::string text;
  const size_t n = std::max(n1, n2);
  for (size_t k = 0; k < n; ++k) {
    CompositionSummary summary;
    const auto [a, b] = commonBlocks(first.layers[n1 > 1 ? k : 0], second.layers[n2 > 1 ? k : 0]);
    auto c = composeCameras(a, b, &summary);
    if (!c) return R::failure((n > 1 ? "layer " + std::to_string(k + 1) + ": " : "") + c.status.message);
    out.layers.push_back(std::move(*c));
    if (k == 0) text = summary.description;
  }
  if (first.pieces) {
    PiecewiseCamera pieces = *first.pieces;
    for (size_t i = 0; i < pieces.patches.size(); ++i) {
      auto c = composeCameras(pieces.patches[i].camera, second.main());
      if (!c) return R::failure("patch " + std::to_string(i) + ": " + c.status.message);
      pieces.patches[i].camera = std::move(*c);
    }
    pieces.source_size = out.sourceSize();
    pieces.target_size = out.targetSize();
    out.pieces = std::move(pieces);
    text += "; " + std::to_string(out.pieces->patches.size()) + " patches composed";
  }
  if (n > 1) text += " (" + std::to_string(n) + " layers, layer by layer)";
  if (description) *description = text;
  return R::success(std::move(out));
}

}  // namespace artcam
