#include "app/cli/warp_attributed.h"

#include "app/cli/commands.h"
#include "core/effects/render_effect.h"
#include "core/io/depth_file.h"
#include "core/model/structure.h"
#include "core/render/attributed.h"

#include <chrono>
#include <cstdio>

namespace artcam::cli {

bool needsAttributedWarp(const ArtcamEffectFile& file) {
  if (!file.extras.layers.empty() || file.extras.depth_output != "depth") return true;
  const CameraStructure s = analyseStructure(file.document.camera);
  return s.attributes_change || s.geometry_depends_on_attributes;
}

int warpAttributed(const ArtcamEffectFile& file, const LoadedImage& image,
                   const AttributedWarpRequest& request) {
  std::optional<ImageF> depth;
  if (request.depth_path) {
    DepthFileOptions o;
    o.scale = request.depth_scale;
    o.baseline_focal = request.baseline_focal;
    DepthFileSummary summary;
    auto read = readDepthFile(*request.depth_path, o, &summary);
    if (!read) throw CommandError(read.status.message);
    depth = std::move(*read);
    std::printf("depth %s: %dx%d, %g..%g, %lld holes\n", request.depth_path->c_str(), depth->width,
                depth->height, summary.min_depth, summary.max_depth, summary.holes);
  }
  AttributedOptions options;
  options.filter = request.warp.filter;
  options.width = request.warp.width;
  options.height = request.warp.height;
  options.threads = request.warp.threads;
  AttributedSummary summary;
  AttributedImage out;
  Artcam camera;
  camera.layers = file.allLayers();
  camera.depth_output = depthOutputFromName(file.extras.depth_output).value_or(DepthOutput::Depth);
  const auto start = std::chrono::steady_clock::now();
  try {
    // Layers summed; depth of field blurs by the σ² its depth output gives (render_effect.h).
    out = renderEffect(image.image, depth ? &*depth : nullptr, camera, options, &summary);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("cannot render: ") + e.what());
  }
  if (const Status s = writeImage(request.output, out.colour, &image.info); !s)
    throw CommandError(s.message);
  if (request.stats)
    std::fprintf(stderr, "render_ms=%.3f\n",
                 std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  std::printf("wrote %s (%dx%d, %s path, kernel %s, %lld transparent pixels)\n",
              request.output.c_str(), out.colour.width, out.colour.height,
              std::string(attributedPathName(summary.path)).c_str(), summary.kernel.c_str(),
              summary.transparent_pixels);
  return 0;
}

}  // namespace artcam::cli
