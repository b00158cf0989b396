// SPDX-License-Identifier: Apache-2.0
// artcam unfold: the paper's Fig 2 — a building's walls unfolded side by side, each seen
// orthogonally, from a photo, its depth (artcam stereo) and the walls' outlines
// (core/piecewise/unfold_walls.h). Writes the camera; artcam warp renders it.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/io/text_input.h"
#include "core/io/walls_csv.h"
#include "core/piecewise/unfold_walls.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace artcam::cli {

const char* const kUnfoldUsage =
    "usage: artcam unfold PHOTO --depth DEPTH --walls WALLS.csv --focal F -o OUT.artcam\n"
    "                     [--scale S] [--principal X,Y] [--no-roof] [--overwrite] [--json]\n\n"
    "Makes the camera that unfolds a building's walls into one picture (the paper's Fig 2):\n"
    "each wall's plane is fitted to the depth inside its outline, the wall is seen\n"
    "orthogonally, and the walls lie side by side, bottom-aligned, at one scale; a piecewise\n"
    "camera whose patches are the walls. Over a wall shorter than the tallest, the roof the\n"
    "photo shows above it (up to where the depth ends) is stretched to the picture's top;\n"
    "other pixels outside every wall stay empty. Render it\n"
    "with artcam warp PHOTO OUT.artcam -o unfolded.png.\n"
    "WALLS.csv has the header wall,x,y, then rows name,x,y: each wall's corners in the photo in\n"
    "order around it, its first edge the wall's base (bottom-left to bottom-right), the walls\n"
    "left to right (at most 64 walls of 64 corners)\n"
    "(artcam sample stereo-house writes one). DEPTH is a depth map of PHOTO (artcam stereo),\n"
    "read as artcam warp --depth reads it.\n\n"
    "options:\n"
    "  --depth DEPTH      the photo's depth map (required)\n"
    "  --walls WALLS.csv  the walls' outlines (required)\n"
    "  --focal F          the photo's focal length in pixels (required)\n"
    "  --principal X,Y    the principal point in pixels (default: the photo's centre)\n"
    "  --scale S          output pixels per depth unit along the walls (default: the walls\n"
    "                     span the photo's width)\n"
    "  --no-roof          leave the band above shorter walls empty\n"
    "  -o, --output OUT   the camera (.artcam; - for standard output)\n"
    "  --overwrite        replace OUT if it exists (--force is the same)\n"
    "  --json             per wall: name, normal, width, height, depth_samples, plane_rms,\n"
    "                     left_out_share, roof_height, roof_stretch; and the output size\n\n"
    "Example:\n"
    "  artcam sample stereo-house -o house\n"
    "  artcam stereo house/house-left.png house/house-right.png --baseline-focal 140 \\\n"
    "      -o house/depth.exr\n"
    "  artcam unfold house/house-left.png --depth house/depth.exr --walls house/house-walls.csv "
    "\\\n"
    "      --focal 560 -o house/unfold.artcam\n"
    "  artcam warp house/house-left.png house/unfold.artcam -o house/unfolded.png\n";

int unfoldCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--depth", "", true},
                         {"--walls", "", true},
                         {"--focal", "", true},
                         {"--principal", "", true},
                         {"--scale", "", true},
                         {"--no-roof", "", false},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--json", "", false}});
  args.expectPositional(1, "PHOTO");
  const auto out = args.value("--output");
  if (!out) throw UsageError("missing -o OUT.artcam");
  for (const char* required : {"--depth", "--walls", "--focal"})
    if (!args.has(required)) throw UsageError(std::string("missing ") + required);
  UnfoldOptions options;
  options.focal_px = numberOption(args, "--focal", 0.0, 0.0, kUnbounded, Ends::OpenMin);
  options.px_per_unit = numberOption(args, "--scale", 0.0, 0.0, kUnbounded, Ends::OpenMin);
  options.stretch_roof = !args.has("--no-roof");
  if (const auto p = args.value("--principal")) {
    const std::vector<double> xy = parseNumberList(*p, "--principal", 0.0, kMaxFrameSide);
    if (xy.size() != 2) throw UsageError("--principal expects X,Y");
    options.principal_px = {xy[0], xy[1]};
  }
  if (args.has("--json") && isStreamPath(*out))
    throw UsageError("--json prints to standard output: give -o a file");
  const std::string& photo = args.positional()[0];
  checkOutputs(args, {*out}, {photo, *args.value("--depth"), *args.value("--walls")});
  const auto shape = readStoredShape(photo);
  if (!shape) throw CommandError(shape.status.message);
  auto depth = readDepthFile(*args.value("--depth"));
  if (!depth) throw CommandError(depth.status.message);
  auto walls = readWallsCsv(*args.value("--walls"));
  if (!walls) throw CommandError(walls.status.message);
  UnfoldSummary summary;
  auto camera = unfoldWalls(*depth, {shape->width, shape->height}, *walls, options, &summary);
  if (!camera)
    throw CommandError(textInputName(*args.value("--walls")) + ": " + camera.status.message);
  camera->frame = CameraFrame::Upright;  // the walls were marked on the photo as it is shown
  if (const Status s = writeArtcam(*out, *camera); !s) throw CommandError(s.message);
  FILE* report = isStreamPath(*out) ? stderr : stdout;
  if (args.has("--json")) {
    nlohmann::json list = nlohmann::json::array();
    for (const UnfoldedWall& w : summary.walls)
      list.push_back({{"name", w.name},
                      {"normal", {w.normal.x(), w.normal.y(), w.normal.z()}},
                      {"width", w.width},
                      {"height", w.height},
                      {"depth_samples", w.depth_samples},
                      {"plane_rms", w.plane_rms},
                      {"left_out_share", w.left_out_share},
                      {"roof_height", w.roof_height},
                      {"roof_stretch", w.roof_stretch}});
    const nlohmann::json j = {{"output", *out},
                              {"width", summary.size.width},
                              {"height", summary.size.height},
                              {"px_per_unit", summary.px_per_unit},
                              {"walls", list}};
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  for (const UnfoldedWall& w : summary.walls) {
    std::string notes;
    if (w.left_out_share > 0.005)
      notes += ", " + std::to_string(static_cast<int>(100 * w.left_out_share + 0.5)) +
               "% past the seam left out";
    if (w.roof_height > 0) {
      char roof[96];
      std::snprintf(roof, sizeof roof, "; the roof over it (%.3g up) stretched x%.2f",
                    w.roof_height, w.roof_stretch);
      notes += roof;
    }
    std::fprintf(report, "wall %s: %.3g x %.3g, plane from %d depth pixels (rms %.3g)%s\n",
                 w.name.c_str(), w.width, w.height, w.depth_samples, w.plane_rms, notes.c_str());
  }
  std::fprintf(report, "wrote %s (%zu walls unfolded into %dx%d)\n", out->c_str(),
               summary.walls.size(), summary.size.width, summary.size.height);
  return 0;
}

}  // namespace artcam::cli
