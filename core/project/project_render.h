// SPDX-License-Identifier: Apache-2.0
// A saved project rendered headless, and the export render the studio's File ▸ Export uses: one
// function for both, so `artcam export PROJECT` writes the pixels the studio writes.
//
// Export options follow what image editors offer on export: an explicit size, JPEG quality and
// bit depth (passed to core/io/image_io.h), and what to do with pixels the camera leaves
// without a preimage: keep them transparent (the default), fill them with a colour, or crop the
// picture to the largest rectangle whose every pixel is valid (as Hugin's "crop to valid area").
#pragma once

#include "core/io/image_io.h"
#include "core/pipeline/render.h"
#include "core/project/document_camera.h"
#include "core/project/studio_project.h"

#include <array>
#include <functional>
#include <optional>
#include <string>

namespace artcam {

struct ExportOptions {
  int width = 0;   // 0×0: the output-frame rule (render.h); one side 0: the other by aspect
  int height = 0;
  // The resampling filter: warp's default, which the studio's canvas also shows.
  Filter filter = Filter::Bilinear;
  // What the filter reads past the photo's edge (filter.h): transparent by default, as
  // `artcam warp`; extend as the peers (Hugin's nona and fulla, OpenImageIO's clamp).
  EdgeMode edge = EdgeMode::Transparent;
  bool crop_to_valid = false;
  // Linear RGB(A) colour under pixels without a preimage; none: they stay transparent.
  std::optional<std::array<float, 4>> fill;
  // Marks after the render (core/effects/finish.h: pencil, charcoal, painting, cartoon), on
  // the values as they will be stored; empty: none. The project's "finish".
  std::string finish;
  WriteImageOptions write;  // pixel type (bit depth), JPEG quality
};

// A format without alpha (JPEG, by the path's extension) cannot keep pixels transparent: with
// neither a fill nor a crop, `options` gets kFlattenFill, white, as an image editor flattens a
// layer with transparency onto its white background when saving it as JPEG (black corners,
// written without a word, looked like a broken camera). Other paths: `options` unchanged. The
// studio's export and `artcam export` both call it, so they write the same file.
inline constexpr std::array<float, 4> kFlattenFill = {1.0f, 1.0f, 1.0f, 1.0f};
bool outputHoldsAlpha(const std::string& path);
ExportOptions exportOptionsForOutput(ExportOptions options, const std::string& path);

// Pixel rectangle [x0, x1) × [y0, y1).
struct ValidRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};
// The largest-area axis-aligned rectangle of pixels whose alpha (the last channel) is ≥ 0.999;
// empty (0×0) when there is none.
ValidRect largestValidRect(const ImageF& image);

// The export render: full resolution from the linear photo, resampled as `artcam warp` does (in
// the photo's stored domain, core/pipeline/render.h, with ExportOptions::filter), then fill or
// crop. `progress` (may be empty) is polled between tiles; false cancels (summary->cancelled).
// `second`: the image compositing cameras read (RenderInputs::second), or null.
ImageF renderExport(const LoadedImage& photo, const ImageF* depth, const Artcam& camera,
                    const ExportOptions& options, const std::function<bool(double)>& progress,
                    RenderSummary* summary, const ImageF* second = nullptr);

// A project with everything its render reads: the photo, the camera made from its pairs,
// colour block and effect stack, and the depth of its planes and map at the photo's size.
struct ProjectScene {
  LoadedImage photo;
  DocumentFit fit;
  DocumentArtcam camera;
  ImageF depth;  // (coverage·z, coverage) at the photo's size; empty: no depth
  // The project's second image (linear, premultiplied RGBA) for compositing effects; empty: none.
  ImageF second;
};

// Reads the photo and the depth map the project names. Messages name the file that failed.
Result<ProjectScene> loadProjectScene(const StudioProject& project, const std::string& where,
                                      const ReadImageOptions& photo_read = {});

// The painted planes (with three anchors each) over the map, at the photo's size; `has_depth`
// says whether any pixel got a depth. The studio's depth model makes the same raster.
ImageF rasteriseProjectDepth(const std::vector<ProjectDepthLayer>& layers, FrameSize photo,
                             const ImageF* map, bool* has_depth);

// A depth raster (coverage·z, coverage) as a depth map file holds it: 1 channel of depth z,
// 0 where there is none (core/io/depth_file.h reads it back). Write it as float EXR.
ImageF depthMapImage(const ImageF& raster);

// depthMapImage(raster) written as float OpenEXR with its one channel named Z, the name
// compositors and `artcam warp --depth` users look for (readDepthFile reads the first channel
// whatever its name). Atomic, as every image write; `progress` as WriteImageOptions::progress.
Status writeDepthMapFile(const std::string& path, const ImageF& raster,
                         const std::function<bool(double)>& progress = {});

}  // namespace artcam
