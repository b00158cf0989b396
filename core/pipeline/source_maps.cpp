// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/source_maps.h"

#include "core/model/structure.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/render.h"

#include <stdexcept>

namespace artcam {

namespace {

const char* blockName(BlockKind kind) {
  switch (kind) {
    case BlockKind::Position: return "position block";
    case BlockKind::Colour: return "colour block";
    case BlockKind::Depth: return "depth block";
    case BlockKind::SecondColour: return "second-colour block";
    case BlockKind::Shading:
      return "shading block";
  }
  return "block";
}

}  // namespace

long long SourceMaps::transparentPixels() const {
  if (layers.empty()) return 0;
  if (layers.size() == 1) return layers[0].map.transparentPixels();
  long long n = 0;
  const size_t count = layers[0].map.preimage.size();
  for (size_t k = 0; k < count; ++k) {
    bool reads = true;
    for (const SourceMapLayer& layer : layers) reads = reads && layer.map.preimage[k] == Preimage::InPhoto;
    n += !reads;
  }
  return n;
}

Result<SourceMaps> sourceMaps(const Artcam& camera, FrameSize target_px,
                              const SourceMapsOptions& options) {
  using R = Result<SourceMaps>;
  std::vector<CameraStructure> structures;
  if (const Status s = validateArtcam(camera, &structures); !s) return R::failure(s.message);
  if (!camera.sourceSize().isImage())
    return R::failure("an ST map needs an image camera (this one is 3D)");
  const FrameSize source = options.source_px.isImage() ? options.source_px : camera.sourceSize();
  for (const CameraStructure& s : structures)
    if (s.geometry_depends_on_attributes)
      return R::failure(
          "this camera's positions depend on colour or depth (eq 8/9), so where a pixel comes "
          "from depends on the photo; no ST map can hold it");
  PositionMapOptions positions = options.positions;
  positions.threads = options.threads;
  SourceMaps maps;
  try {
    if (camera.pieces) {
      // The render's mesh (core/pipeline/render.cpp, piecewiseOptions): the same step rule and
      // rasteriser, so the map is the inverse the piecewise warp samples, seams and all.
      PiecewiseRenderOptions p;
      p.mesh_step_px = options.mesh_step_px;
      p.threads = options.threads;
      maps.layers.push_back({"", piecewisePositionMap(*camera.pieces, source, target_px, p)});
      maps.kernel = "piecewise mesh, " + std::to_string(camera.pieces->patches.size()) + " patches";
      return R::success(std::move(maps));
    }
    if (camera.layers.size() > 1) {
      const std::vector<Camera> channels = channelCameras(camera);
      if (channels.empty())
        return R::failure("its " + std::to_string(camera.layers.size()) +
                          " layers change colour and are summed (eq 5), which no ST map per "
                          "layer can say; only per-channel layers (chromatic aberration: each "
                          "layer moves one colour channel) have one map per channel");
      static const char* const kNames[3] = {"R", "G", "B"};
      maps.kernel = "per-channel ";
      for (size_t k = 0; k < channels.size(); ++k) {
        PositionMap map = sourcePositionMap(channels[k], source, target_px, positions);
        maps.kernel += (k ? "+" : "") + map.kernel;
        maps.layers.push_back({kNames[k], std::move(map)});
      }
      return R::success(std::move(maps));
    }
    const Camera& main = camera.main();
    // What the warp does beyond moving pixels. An ST map only moves them (a compositor grades
    // separately), so the map is written and these are named, not refused.
    if (structures[0].attributes_change)
      for (const Block& block : main.blocks())
        if (block.kind != BlockKind::Position) maps.left_out.push_back(blockName(block.kind));
    if (camera.depth_output == DepthOutput::BlurVariance)
      maps.left_out.push_back("depth-of-field blur");
    PositionMap map = sourcePositionMap(main, source, target_px, positions);
    maps.kernel = map.kernel;
    maps.layers.push_back({"", std::move(map)});
  } catch (const std::invalid_argument& e) {
    return R::failure(e.what());
  }
  return R::success(std::move(maps));
}

}  // namespace artcam
