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
