// SPDX-License-Identifier: Apache-2.0
// The studio's project file (.artcamproj) as a value, with its one reader and writer: what
// artcam-studio saves and reopens and what `artcam export` renders headless, so both read a
// project the same way.
//
//   { "format": "artcam-studio-project", "version": 5,
//     "photo": "relative/or/absolute/path.png",
//     "photo_size": [w, h],                          // optional: the photo's size when saved
//     "model": "auto",
//     "line_model": "radial",                    // optional, v4: the lines' model; absent: auto
//     "pairs": [ {"source": [x, y], "target": [x, y], "enabled": true}, … ],   // photo pixels
//     "camera": { ….artcam document… },          // optional: camera set by hand (any kind)
//     "effects": [ {"effect": "aerial-perspective", "params": {"near": [1], …}}, … ],  // v3
//     "lines": [ {"label": "1", "points": [[x, y], …], "enabled": true,
//                 "role": "horizontal"}, … ],   // v4, photo px; role optional (or "vertical")
//     "second": {"path": "over.png"},               // v5: the image compositing effects read
//     "finish": "pencil",                           // v5: marks after the render (G'MIC)
//     "view": { … },                                // the studio's view state (opaque here)
//     "depth": {                                    // optional: depth planes and map (v2)
//       "layers": [ {"name": "Plane 1", "size": [w, h], "mask": "<base64 of run bytes>",
//                    "anchors": [ {"pixel": [x, y], "depth": z}, … ] }, … ],
//       "map": {"path": "depth.exr", "scale": 1, "inverse": false} },
//     "parts": { "colour": {…, "colour_block": {….artcam…}}, "insertion": {…} } }   // (v2)
//
// Versions: a file is written with the lowest version that holds everything in it (1: pairs
// and view; 2: depth or parts; 3: an effect stack; 4: straight lines; 5: a second image or a
// finish), so an
// older studio refuses a project whose new parts it would silently drop and still opens every
// project it can represent fully. This reader takes 1 to 5.
//
// Decisions:
// - "photo_size" records the size the pairs, lines and masks were made on, so a photo located
//   in another place (it moved) can be checked before anything is laid on it. Older readers
//   ignore it, so it needs no new version; a project without it falls back on its masks' size
//   and the hand-set camera's source frame (projectPhotoSize).
// - The view state and the studio modes' parts are kept as JSON text: they belong to the
//   studio (ui/project_file.h reads them), and a headless reader must carry them through
//   unchanged. The one part core reads is the colour block (parts/colour/colour_block), because
//   it is part of the camera the project renders.
// - Paths are stored relative to the project's folder when the file lies beneath it, and are
//   absolute once read.
// - Every refusal is one line naming the file and the JSON path ("p.artcamproj: /pairs/3/source:
//   expected [x, y]"). Sizes that would allocate are checked before allocating (a depth mask's
//   size against its run bytes).
// - One memory budget for the whole document (core/util/memory_budget.h), checked from the
//   sizes the JSON states before any mask is decoded: every mask (a byte per pixel), the one
//   being decoded (a byte per pixel more) and the photo the masks were painted on (they are
//   the photo's size), as float RGBA with its depth raster (kProjectPhotoBytesPerPixel). A
//   few bytes of JSON cannot ask for gigabytes; the refusal names /depth/layers and the budget.
//   checkProjectMemory adds the photo's real size from its header before it is decoded.
#pragma once

#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "core/effects/effect_table.h"
#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"
#include "core/io/depth_file.h"
#include "core/model/artcam.h"
#include "core/model/line_trace.h"
#include "core/model/status.h"

#include <optional>
#include <string>
#include <vector>

namespace artcam {

inline constexpr int kProjectFormatVersion = 5;   // the newest this code reads and writes
inline constexpr int kMaxDepthAnchors = 3;        // a plane in inverse depth needs three
// An effect stack longer than this is refused: each effect composes with the camera so far,
// so a stack's work grows faster than its length, and no picture needs hundreds of effects.
inline constexpr size_t kMaxProjectEffects = 256;
inline constexpr char kProjectExtension[] = "artcamproj";

struct ProjectDepthLayer {
  std::string name;
  RegionMask mask;                   // the photo's size
  std::vector<DepthAnchor> anchors;  // up to kMaxDepthAnchors
  bool operator==(const ProjectDepthLayer&) const = default;
};

struct ProjectDepthMap {
  std::string path;  // absolute once read
  DepthFileOptions options;
};

// One entry of the effect stack: an effect of the effects table with every parameter it was
// given (missing ones take the table's defaults when the camera is built).
struct EffectStep {
  std::string effect;
  EffectValues values;
  bool operator==(const EffectStep&) const = default;
};

struct StudioProject {
  std::string photo_path;  // absolute once read
  std::optional<FrameSize> photo_size;  // the photo's size when saved; none: not recorded
  std::vector<PointMatch> pairs;  // photo pixels, 2D
  std::vector<LineTrace> lines;   // straight edges traced in the photo (photo pixels)
  ModelClass model = ModelClass::Auto;
  LineModel line_model = LineModel::Auto;  // the model chosen for the lines ("line_model")
  std::optional<Artcam> manual_camera;
  std::vector<EffectStep> effects;  // applied in order after the geometry and colour
  std::vector<ProjectDepthLayer> depth_layers;
  std::optional<ProjectDepthMap> depth_map;
  // The second image the colour block's compositing operators read (over, in, atop, xor,
  // multiply, screen, …: core/colour/composite.h), laid over the photo's frame ("second":
  // {"path": …}); absolute once read. None: compositing effects are left out.
  std::optional<std::string> second_path;
  // Marks after the render (core/effects/finish.h), by name; empty: none ("finish", v5).
  std::string finish;
  std::string view_json;   // the "view" object as JSON text; empty: none
  std::string parts_json;  // the "parts" object as JSON text; empty: none
};

// Bytes per photo pixel a document holds beside its masks: the float RGBA photo (16) and the
// depth raster the planes make at its size (coverage·z and coverage, 8).
inline constexpr double kProjectPhotoBytesPerPixel = 24.0;

// The memory budget for the whole document `project` with a photo of `photo` pixels of
// `photo_channels` channels (its header's; 0×0: not known yet, the masks' size stands for it):
// fails "WHERE: /depth/layers: …" or "WHERE: photo: …", naming the budget, when masks, photo
// and depth raster together would not fit it. Masks are counted as parseStudioProject holds
// them; the photo is not decoded yet.
Status checkProjectMemory(const StudioProject& project, FrameSize photo, int photo_channels,
                          const std::string& where);

// The colour block the project's colour part holds (parts/colour/colour_block), if any.
// `where` names the file in messages.
Result<std::optional<Camera>> projectColourBlock(const StudioProject& project,
                                                 const std::string& where);

// The size of photo the project's pixels belong to: photo_size, else the first depth mask's
// size, else the hand-set camera's source frame; none when the project records none of them.
std::optional<FrameSize> projectPhotoSize(const StudioProject& project);

// A photo of `photo` pixels in place of the project's: fails "WHERE: PHOTO is WxH but the
// project was made on a WxH photo" when the project's size (projectPhotoSize) differs.
Status checkProjectPhotoSize(const StudioProject& project, FrameSize photo,
                             const std::string& photo_path, const std::string& where);

// `project_path` places relative paths and names the file in messages.
Result<StudioProject> parseStudioProject(std::string_view text, const std::string& project_path);
Result<StudioProject> readStudioProject(const std::string& path);
std::string studioProjectToJson(const StudioProject& project, const std::string& project_path);
// Atomic (core/io/atomic_file.h): the old file stays whole until the new one is complete.
Status writeStudioProject(const std::string& path, const StudioProject& project);

}  // namespace artcam
