// SPDX-License-Identifier: Apache-2.0
// ST maps: a camera's inverse map as a float EXR other tools warp with (Nuke's STMap node,
// Fusion's and Resolve's STMap tools, OpenImageIO's ImageBufAlgo::st_warp, OpenCV's cv::remap),
// and the reader that turns a map made elsewhere back into point matches for the fit.
//
// Conventions. Output pixel (i, j) of the map holds the SOURCE position (x, y) it reads, in
// source pixels with centres at i + 0.5 and y down (frames.h). Which pixels read nothing is
// position_map.h's rule, the warp's own: no preimage, or a preimage beyond the bilinear
// filter's reach of the photo (more than half a pixel outside it); `artcam warp` leaves exactly
// those transparent.
// - StMap (Nuke, Fusion, Resolve, OIIO st_warp): channels R, G, B, A, 32-bit float.
//   R = x / W, G = 1 − y / H (W × H the source size; t counts up from the bottom edge), B = 0,
//   A = 1 where the warp reads the photo and 0 where it leaves the pixel transparent. There R
//   and G still hold the position when there is one (outside the photo: the camera's geometry,
//   which the reader keeps as a match); with no preimage R = G = 0. So multiplying a warp
//   through the map by A gives `artcam warp`'s transparent pixels whatever the tool does at
//   the border (a compositor that clamps would otherwise smear the edge into them). st_warp
//   samples the source at (s·W, (1 − t)·H) when its flip_t is on, which is this convention;
//   Nuke measures y from the bottom edge, so its STMap node reads t as it is.
// - OpenCv (cv::remap): channels R = map_x, G = map_y, 32-bit float, in cv::remap's pixels,
//   whose centres are at integers: map_x = x − 0.5, map_y = y − 0.5, kept outside the photo
//   (remap with a constant 0 border reads nothing there, as the warp), and −1 in both where the
//   pixel has no preimage (also nothing under that border).
//   Named R and G (not map_x, map_y) so readers that know only colour channels load them;
//   OpenCV orders colour channels B, G, R, so read them by name (OpenImageIO) or mind that
//   order. Only OpenImageIO reading is tested here.
// Layered maps (a per-channel camera: chromatic aberration) hold one map per layer in one EXR,
// each layer's channels prefixed by its name: "R.R", "R.G", "R.B", "R.A" for the map that moves
// the photo's R channel, then "G.…", "B.…"; the header's "artcam:layers" lists the names
// ("R,G,B"). Nuke reads each as a layer of its own (R, G, B) for its STMap node's UV channels.
// Both files carry the header attributes "artcam:convention" ("stmap" or "opencv") and
// "artcam:source_width" / "artcam:source_height", which the reader uses when present: an
// ST map is normalised, so its source size is not otherwise in it.
#pragma once

#include "core/model/fit_record.h"
#include "core/model/status.h"
#include "core/render/position_map.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class StmapConvention { StMap, OpenCv };
std::string_view stmapConventionName(StmapConvention convention);  // "stmap", "opencv"
std::optional<StmapConvention> stmapConventionFromName(std::string_view name);

// One map of a file: `name` empty for a file of one map (channels R, G, B, A), else the layer's
// name (its channels "name.R", …). Borrowed.
struct StmapLayer {
  std::string name;
  const PositionMap* map = nullptr;
};

// The values one pixel `k` of `map` is stored as: StMap R, G, B, A (A = 1 only where the warp
// reads the photo, position_map.h; a preimage outside the photo keeps its position; no preimage
// is R = G = 0), OpenCv map_x, map_y (−1 for no preimage). What writeStmap writes and the
// Python module's export_map returns.
inline int stmapChannelCount(StmapConvention convention) {
  return convention == StmapConvention::StMap ? 4 : 2;
}
inline void stmapPixel(const PositionMap& map, size_t k, StmapConvention convention, float* p) {
  const Preimage pre = map.preimage[k];
  const double sx = map.x_px[k], sy = map.y_px[k];
  const double w = map.source_px.width, h = map.source_px.height;
  if (convention == StmapConvention::StMap) {
    p[0] = pre != Preimage::None ? static_cast<float>(sx / w) : 0.0f;
    p[1] = pre != Preimage::None ? static_cast<float>(1.0 - sy / h) : 0.0f;
    p[2] = 0.0f;
    p[3] = pre == Preimage::InPhoto ? 1.0f : 0.0f;
  } else {
    // A position outside the photo reads nothing under remap's constant border, as the warp's
    // transparent pixel; −1 marks no preimage (it too reads nothing there).
    p[0] = pre != Preimage::None ? static_cast<float>(sx - 0.5) : -1.0f;
    p[1] = pre != Preimage::None ? static_cast<float>(sy - 0.5) : -1.0f;
  }
}

// Writes atomically; errors name the file and the cause. Throws std::invalid_argument for no
// layer, layers of different frames, or an unnamed layer among several.
Status writeStmap(const std::string& path, const std::vector<StmapLayer>& layers,
                  StmapConvention convention);

struct StmapSampleOptions {
  // Grid step in map pixels; 0 picks the smallest step that keeps at most max_matches samples.
  int step = 0;
  int max_matches = 4000;
  // The source size the map's normalised positions are scaled by; empty: the file's
  // artcam:source_width/height, else the map's own size (a lens map of one plate).
  std::optional<FrameSize> source_px;
  // A layered map's layer to read ("R", "G", "B"; case-insensitive); empty: a map of one layer.
  std::string layer;
};

struct StmapSamples {
  std::vector<PointMatch> matches;  // source (x, y) px → target pixel centre (i + 0.5, j + 0.5)
  FrameSize map_px;  // the target frame: the map's display window (EXR), else its size
  FrameSize source_px;
  StmapConvention convention = StmapConvention::StMap;
  int step = 1;
  bool has_alpha = false;
};

// Reads an ST map (either convention, from the artcam:convention attribute; StMap when absent)
// and samples its data window every `step` pixels (targets in display-window pixels, so an
// overscan map's border samples have targets outside the frame), keeping pixels with a preimage
// (finite values; alpha > 0 where there is an alpha channel, or alpha 0 with a position beyond
// the photo's edge, as export-map writes a preimage outside the photo; not −1 for OpenCv maps).
// Refuses, in one line naming the file, a map without R and G channels, a layered map without
// options.layer (or a layer it lacks), an unknown convention attribute, or one with no usable
// pixel on the grid.
Result<StmapSamples> readStmapSamples(const std::string& path,
                                      const StmapSampleOptions& options = {});

}  // namespace artcam
