// artcam warp for attributed cameras (issue 6): cameras that change colour or depth, layered
// cameras (chromatic aberration) and depth of field go to core/render/attributed.h instead of
// the geometry-only gather warp.
#pragma once

#include "app/cli/args.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/render/warp.h"

#include <optional>
#include <string>

namespace artcam::cli {

// True when the file needs the attributed renderer (layers, a depth-of-field output, or a
// camera whose colour/depth changes or whose geometry reads them).
bool needsAttributedWarp(const ArtcamEffectFile& file);

struct AttributedWarpRequest {
  std::string output;
  std::optional<std::string> depth_path;  // --depth FILE
  double depth_scale = 1.0;               // --depth-scale (integer files)
  double baseline_focal = 0.0;            // --disparity BF: the file holds disparity
  WarpOptions warp;                       // filter, size, threads
  bool stats = false;
};

// Renders and writes OUT; throws CommandError with the file and the cause.
int warpAttributed(const ArtcamEffectFile& file, const LoadedImage& image,
                   const AttributedWarpRequest& request);

}  // namespace artcam::cli
