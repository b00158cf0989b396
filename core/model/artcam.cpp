// SPDX-License-Identifier: Apache-2.0
#include "core/model/artcam.h"

#include "core/model/coverage.h"
#include "core/model/structure.h"

#include <Eigen/LU>

#include <cmath>
#include <stdexcept>

namespace artcam {

std::string_view depthOutputName(DepthOutput output) {
  return output == DepthOutput::BlurVariance ? "blur-variance" : "depth";
}

std::optional<DepthOutput> depthOutputFromName(std::string_view name) {
  if (name == "depth") return DepthOutput::Depth;
  if (name == "blur-variance") return DepthOutput::BlurVariance;
  return std::nullopt;
}

std::string_view cameraFrameName(CameraFrame frame) {
  return frame == CameraFrame::Sensor ? "sensor" : "upright";
}

std::optional<CameraFrame> cameraFrameFromName(std::string_view name) {
  if (name == "sensor") return CameraFrame::Sensor;
  if (name == "upright") return CameraFrame::Upright;
  return std::nullopt;
}

std::string_view artcamKindName(ArtcamKind kind) {
  switch (kind) {
    case ArtcamKind::Single: return "single";
    case ArtcamKind::Chained: return "chained";
    case ArtcamKind::Attributed: return "attributed";
    case ArtcamKind::Layered: return "layered";
    case ArtcamKind::Piecewise: return "piecewise";
  }
  return "single";
}

void Artcam::setFrames(FrameSize source_size, FrameSize target_size) {
  for (Camera& layer : layers) layer.setFrames(source_size, target_size);
  if (pieces) {
    pieces->source_size = source_size;
    pieces->target_size = target_size;
    for (CameraPatch& patch : pieces->patches) patch.camera.setFrames(source_size, target_size);
  }
}

std::vector<std::string> cameraWarnings(const Artcam& camera) {
  std::vector<std::string> warnings;
  for (size_t i = 0; i < camera.layers.size(); ++i) {
    const std::string warning = measureCoverage(camera.layers[i]).warning();
    if (warning.empty()) continue;
    warnings.push_back((i == 0 ? std::string() : "layer " + std::to_string(i) + ": ") + warning);
  }
  if (camera.pieces)
    for (size_t i = 0; i < camera.pieces->patches.size(); ++i) {
      const CameraPatch& p = camera.pieces->patches[i];
      const PatchRect box = camera.pieces->sourceBox(static_cast<int>(i));
      if (!(box.x1 > box.x0 && box.y1 > box.y0)) {
        warnings.push_back("patch " + std::to_string(i) + ": no source pixel reaches it");
        continue;
      }
      const std::string warning =
          measureCoverage(p.camera, {box.x0, box.y0}, {box.x1, box.y1}).warning();
      if (!warning.empty()) warnings.push_back("patch " + std::to_string(i) + ": " + warning);
    }
  return warnings;
}

bool readsDepth(const Artcam& camera) {
  for (const Block& b : camera.blocks())
    if (b.kind == BlockKind::Depth) return true;
  return false;
}

ArtcamKind Artcam::kind() const {
  if (pieces) return ArtcamKind::Piecewise;
  if (layers.size() > 1) return ArtcamKind::Layered;
  const Camera& c = main();
  const bool position_only = c.blocks().size() == 1 && c.blocks()[0].kind == BlockKind::Position;
  if (!position_only || depth_output != DepthOutput::Depth) return ArtcamKind::Attributed;
  return c.stages().size() > 1 ? ArtcamKind::Chained : ArtcamKind::Single;
}

namespace {

std::string sizeText(FrameSize s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

// A stage whose every tensor is zero maps every point to 0: nothing is defined anywhere.
bool hasZeroStage(const Camera& camera) {
  for (const Stage& stage : camera.stages()) {
    bool all_zero = true;
    for (const Eigen::MatrixXd& q : stage.q) all_zero = all_zero && q.isZero(0.0);
    if (all_zero) return true;
  }
  return false;
}

// `rect_px`: the source rectangle the camera answers for (a patch's), else the whole frame.
// `structure` (may be null) receives the camera's structure analysis, made here once for the
// coverage check and kept for the caller's render.
Status checkCamera(const Camera& camera, const std::string& where,
                   const PatchRect* rect_px = nullptr, CameraStructure* structure = nullptr) {
  try {
    camera.validate();
  } catch (const std::invalid_argument& e) {
    return Status::failure(where + e.what());
  }
  if (camera.stages().empty()) return Status::failure(where + "no stages");
  if (hasZeroStage(camera))
    return Status::failure(where + "every tensor of a stage is zero (the camera maps nothing)");
  CameraStructure analysed = analyseStructure(camera);
  const Coverage coverage =
      rect_px ? measureCoverage(camera, analysed, {rect_px->x0, rect_px->y0}, {rect_px->x1, rect_px->y1})
              : measureCoverage(camera, analysed);
  if (structure) *structure = std::move(analysed);
  if (const Status s = coverage.status(); !s) return Status::failure(where + s.message);
  return Status::success();
}

bool finite(const PatchRect& r) {
  return std::isfinite(r.x0) && std::isfinite(r.y0) && std::isfinite(r.x1) && std::isfinite(r.y1);
}

Status checkPieces(const Artcam& camera) {
  const PiecewiseCamera& pieces = *camera.pieces;
  const Camera& main = camera.main();
  if (camera.layers.size() != 1) return Status::failure("/patches: a piecewise camera has one layer");
  if (main.blocks().size() != 1 || main.blocks()[0].kind != BlockKind::Position ||
      main.blocks()[0].size != 3 || !main.sourceSize().isImage())
    return Status::failure("/patches: patches need a position-only image camera");
  if (pieces.patches.empty()) return Status::failure("/patches: no patches");
  if (pieces.patches.size() > static_cast<size_t>(kMaxPatches))
    return Status::failure("/patches: " + std::to_string(pieces.patches.size()) +
                           " patches, more than the " + std::to_string(kMaxPatches) + " allowed");
  if (!std::isfinite(pieces.support_margin_px) || pieces.support_margin_px < 0.0)
    return Status::failure("/support_margin_px: expected a number ≥ 0");
  if (pieces.source_size != main.sourceSize() || pieces.target_size != main.targetSize())
    return Status::failure("/patches: frames differ from the camera's");
  if (pieces.patch_frame) {
    const Eigen::Matrix3d& h = pieces.patch_frame->patch_from_source;
    if (!pieces.patch_frame->size.isImage())
      return Status::failure("/patch_frame/size: expected an image frame");
    if (!h.allFinite() || !(std::abs(h.determinant()) > 0.0) || !std::isfinite(h.determinant()))
      return Status::failure("/patch_frame/patch_from_source_px: not a finite invertible homography");
  }
  // Rectangles and hulls are in the patch frame (the source frame unless a homography was
  // composed before the patches).
  const FrameSize src = pieces.patchFrameSize();
  // A rectangle may reach a pixel beyond the frame (quadtree cells are rounded outwards).
  constexpr double kSlack = 1.0;
  for (size_t i = 0; i < pieces.patches.size(); ++i) {
    const CameraPatch& p = pieces.patches[i];
    const std::string where = "/patches/" + std::to_string(i);
    if (!finite(p.rect)) return Status::failure(where + "/rect: not finite");
    if (!(p.rect.x1 > p.rect.x0 && p.rect.y1 > p.rect.y0))
      return Status::failure(where + "/rect: x1 must exceed x0 and y1 must exceed y0");
    if (p.rect.x0 < -kSlack || p.rect.y0 < -kSlack || p.rect.x1 > src.width + kSlack ||
        p.rect.y1 > src.height + kSlack)
      return Status::failure(where + "/rect: outside the " + sizeText(src) + " source frame");
    for (const Eigen::Vector2d& v : p.support)
      if (!v.allFinite()) return Status::failure(where + "/support: not finite");
    if (p.camera.blocks() != main.blocks() || p.camera.sourceSize() != main.sourceSize() ||
        p.camera.targetSize() != main.targetSize())
      return Status::failure(where + "/camera: blocks and frames must match the top-level camera's");
    // Coverage over the source pixels the patch answers for; a patch no source pixel reaches
    // (possible only behind a patch frame) is harmless, and cameraWarnings says so.
    const PatchRect box = pieces.sourceBox(static_cast<int>(i));
    if (!(box.x1 > box.x0 && box.y1 > box.y0)) {
      try {
        p.camera.validate();
      } catch (const std::invalid_argument& e) {
        return Status::failure(where + "/camera: " + e.what());
      }
      continue;
    }
    if (Status s = checkCamera(p.camera, where + "/camera: ", &box); !s) return s;
  }
  // Patches tile the source: neighbours share edges, interiors never overlap — unless both
  // patches have support hulls whose interiors are apart (every renderer asks a patch only
  // inside its support grown by the margin, so a source pixel still has one patch).
  for (size_t i = 0; i < pieces.patches.size(); ++i)
    for (size_t j = i + 1; j < pieces.patches.size(); ++j) {
      const PatchRect& a = pieces.patches[i].rect;
      const PatchRect& b = pieces.patches[j].rect;
      const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
      const double h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
      if (w > 1e-6 && h > 1e-6 &&
          !convexInteriorsApart(pieces.patches[i].support, pieces.patches[j].support,
                                2.0 * pieces.support_margin_px))
        return Status::failure("/patches/" + std::to_string(j) + "/rect: overlaps patch " +
                               std::to_string(i));
    }
  return Status::success();
}

}  // namespace

Status validateArtcam(const Artcam& camera, std::vector<CameraStructure>* layer_structures) {
  if (camera.layers.empty()) return Status::failure("/stages: the camera has no layers");
  const Camera& main = camera.main();
  // Every layer and patch shares these frames (checked below), so the main camera's say it.
  for (const auto& [frame, name] :
       {std::pair{main.sourceSize(), "source"}, std::pair{main.targetSize(), "target"}})
    if (frame.width > kMaxFrameSide || frame.height > kMaxFrameSide)
      return Status::failure(std::string("/frames/") + name + ": " + sizeText(frame) +
                             " has a side beyond the " + std::to_string(kMaxFrameSide) +
                             " pixels a camera's frame may have");
  if (layer_structures) layer_structures->assign(camera.layers.size(), CameraStructure{});
  for (size_t i = 0; i < camera.layers.size(); ++i) {
    const std::string where = i == 0 ? std::string("/stages: ") : "/layers/" + std::to_string(i - 1) + ": ";
    CameraStructure* structure = layer_structures ? &(*layer_structures)[i] : nullptr;
    if (Status s = checkCamera(camera.layers[i], where, nullptr, structure); !s) return s;
    if (i > 0 && (camera.layers[i].blocks() != main.blocks() ||
                  camera.layers[i].sourceSize() != main.sourceSize() ||
                  camera.layers[i].targetSize() != main.targetSize()))
      return Status::failure(where + "blocks and frames must match the main camera's");
  }
  if (camera.depth_output == DepthOutput::BlurVariance && main.layout().find(BlockKind::Depth) < 0)
    return Status::failure("/depth_output: \"blur-variance\" needs a depth block");
  if (camera.pieces) return checkPieces(camera);
  return Status::success();
}

}  // namespace artcam
