// SPDX-License-Identifier: Apache-2.0
// artcam export-map: a camera's inverse map as an ST map other tools warp with
// (core/io/stmap_file.h has the conventions).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "core/io/artcam_file.h"
#include "core/io/stmap_file.h"
#include "core/render/position_map.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <stdexcept>

namespace artcam::cli {

const char* const kExportMapUsage =
    "usage: artcam export-map CAM.artcam --size WxH -o MAP.exr [--convention stmap|opencv]\n"
    "                         [--overwrite] [--json]\n\n"
    "Writes the camera's inverse map: for each pixel of a WxH output, the source position it\n"
    "reads, exactly where artcam warp reads it (the same coordinate kernels), as a 32-bit float\n"
    "OpenEXR that Nuke, Fusion, Resolve, OpenImageIO and OpenCV warp with. Pixels: centres at\n"
    "i + 0.5, y down; W x H below is the camera's source frame size.\n"
    "  --convention stmap (default): the Nuke/Fusion/Resolve STMap. Channels R, G, B, A:\n"
    "      R = x / W, G = 1 - y / H (t up), B = 0, A = 1; where the pixel has no preimage\n"
    "      (beyond the camera's pole curve, folded) R = G = A = 0. OpenImageIO's st_warp with\n"
    "      flip_t reads it as it is; Nuke's STMap node with UV channels rgb.\n"
    "  --convention opencv: cv::remap's map_x, map_y in channels R and G (pixel centres at\n"
    "      integers: map_x = x - 0.5, map_y = y - 0.5), -1 in both where there is no preimage.\n"
    "      Read them by name; OpenCV's own readers order colour channels B, G, R.\n"
    "The header keeps artcam:convention and the source size (artcam:source_width,\n"
    "artcam:source_height), which artcam fit --stmap reads back.\n"
    "A piecewise or layered camera (chromatic aberration), or one whose positions depend on\n"
    "colour or depth, has no single map and is refused.\n\n"
    "options:\n"
    "  --size WxH      the map's size, the output frame (required; at most 2^27 pixels)\n"
    "  -o/--output     the map file (required, .exr; written atomically); an existing one is\n"
    "                  refused unless --overwrite (--force is the same)\n"
    "  --convention    stmap (default) or opencv\n"
    "  --json          print {\"output\", \"width\", \"height\", \"convention\", \"kernel\",\n"
    "                  \"invalid_pixels\"}\n\n"
    "Example:\n"
    "  artcam export-map lens.artcam --size 1920x1080 -o lens-stmap.exr\n";

int exportMapCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--size", "", true},
                         {"--convention", "", true},
                         {"--json", "", false},
                         {"--overwrite", "", false},
                         {"--force", "", false}});
  args.expectPositional(1, "CAM.artcam");
  const std::string& path = args.positional()[0];
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o MAP.exr");
  const auto size_text = args.value("--size");
  if (!size_text) throw UsageError("missing --size WxH (the map's size, the output frame)");
  const FrameSize size = parseSize(*size_text, "--size");
  // The map is held in memory (9 bytes a pixel) before it is written: 2^27 pixels (e.g.
  // 16384x8192) is about 1.2 GB, past any plate a compositor warps.
  if (static_cast<long long>(size.width) * size.height > (1LL << 27))
    throw UsageError("--size " + *size_text + " is too large for a map (at most 2^27 pixels)");
  const std::string convention_name = args.valueOr("--convention", "stmap");
  const auto convention = stmapConventionFromName(convention_name);
  if (!convention)
    throw UsageError("--convention expects stmap or opencv, not \"" + convention_name + "\"");
  checkOutputs(args, {*output}, {path});

  const auto camera = readArtcam(path);
  if (!camera) throw CommandError(camera.status.message);
  for (const std::string& warning : cameraWarnings(*camera))
    std::fprintf(stderr, "artcam export-map: warning: %s: %s\n", path.c_str(), warning.c_str());
  if (camera->pieces)
    throw CommandError(path +
                       ": a piecewise camera has one map per patch; export-map needs a "
                       "single camera");
  if (camera->layers.size() > 1)
    throw CommandError(path + ": a layered camera (" + std::to_string(camera->layers.size()) +
                       " layers) moves each layer differently; export-map needs one layer");
  const Camera& main = camera->main();
  if (!main.sourceSize().isImage())
    throw CommandError(path + ": export-map needs an image camera (this one is 3D)");
  PositionMap map;
  try {
    map = sourcePositionMap(main, main.sourceSize(), size);
  } catch (const std::invalid_argument& e) {
    throw CommandError(path + ": " + e.what());
  }
  if (const Status s = writeStmap(*output, map, *convention); !s) throw CommandError(s.message);
  if (args.has("--json")) {
    const nlohmann::json j = {
        {"output", *output},     {"width", size.width},
        {"height", size.height}, {"convention", std::string(stmapConventionName(*convention))},
        {"kernel", map.kernel},  {"invalid_pixels", map.invalid_pixels}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%s map %dx%d (%s kernel), %lld pixels without a preimage\nwrote %s\n",
                std::string(stmapConventionName(*convention)).c_str(), size.width, size.height,
                map.kernel.c_str(), map.invalid_pixels, output->c_str());
  }
  return 0;
}

}  // namespace artcam::cli
