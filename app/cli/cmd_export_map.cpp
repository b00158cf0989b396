// SPDX-License-Identifier: Apache-2.0
// artcam export-map: a camera's inverse map as an ST map other tools warp with
// (core/io/stmap_file.h has the conventions).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/io/stmap_file.h"
#include "core/pipeline/source_maps.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace artcam::cli {

const char* const kExportMapUsage =
    "usage: artcam export-map CAM.artcam --size WxH -o MAP.exr [--convention stmap|opencv]\n"
    "                         [--source-size WxH] [--overwrite] [--json]\n\n"
    "Writes the camera's inverse map: for each pixel of a WxH output, the source position it\n"
    "reads, exactly where artcam warp reads it (the same coordinate kernels; for a piecewise\n"
    "camera the same mesh), as a 32-bit float OpenEXR that Nuke, Fusion, Resolve, OpenImageIO\n"
    "and OpenCV warp with. Pixels: centres at i + 0.5, y down; W x H below is the size of the\n"
    "photo the map will warp (--source-size, default the camera's source frame). A pixel\n"
    "reads nothing where it has no preimage (beyond the camera's pole curve, folded) or its\n"
    "preimage lies more than half a pixel outside the photo: there artcam warp makes it\n"
    "transparent, and the map says so.\n"
    "  --convention stmap (default): the Nuke/Fusion/Resolve STMap. Channels R, G, B, A:\n"
    "      R = x / W, G = 1 - y / H (t up), B = 0, A = 1 where the pixel reads the photo and 0\n"
    "      where artcam warp leaves it transparent (R, G keep a position outside the photo;\n"
    "      R = G = 0 with no preimage). Multiply the warped result by A. OpenImageIO's st_warp\n"
    "      with flip_t reads it as it is; Nuke's STMap node with UV channels rgb.\n"
    "  --convention opencv: cv::remap's map_x, map_y in channels R and G (pixel centres at\n"
    "      integers: map_x = x - 0.5, map_y = y - 0.5; -1 in both with no preimage), for remap\n"
    "      with a constant 0 border. Read them by name; OpenCV's own readers order B, G, R.\n"
    "Cameras: a position camera has one map; a piecewise camera one map of its mesh; a\n"
    "per-channel camera (chromatic aberration, lens camera with TCA) one map per colour\n"
    "channel in the same file, its channels named R.R, R.G, R.B, R.A, G.R, ... (layer = the\n"
    "photo channel it moves). An attributed camera's map is its position part: what it does to\n"
    "colour or depth (colour, depth, second-colour blocks, depth-of-field blur) is not in an ST\n"
    "map and a warning names it. Refused: cameras whose positions depend on colour or depth,\n"
    "layers that change colour and are summed, 3D cameras.\n"
    "The header keeps artcam:convention, the source size (artcam:source_width,\n"
    "artcam:source_height) and a layered map's artcam:layers, which artcam fit --stmap reads\n"
    "back. docs/user-guide.md has the recipes that reproduce artcam warp from a map.\n\n"
    "options:\n"
    "  --size WxH      the map's size, the output frame (required; at most 2^27 pixels, all\n"
    "                  layers together)\n"
    "  -o/--output     the map file (required, .exr; written atomically); an existing one is\n"
    "                  refused unless --overwrite (--force is the same)\n"
    "  --convention    stmap (default) or opencv\n"
    "  --source-size WxH  the photo the map will warp (default: the camera's source frame);\n"
    "                  positions are in its pixels, and the half-pixel border where a pixel\n"
    "                  still reads the photo (and a piecewise camera's mesh) follow it\n"
    "  --json          print {\"output\", \"width\", \"height\", \"convention\", \"kernel\",\n"
    "                  \"layers\", \"invalid_pixels\", \"transparent_pixels\", \"left_out\"}\n\n"
    "Example:\n"
    "  artcam export-map lens.artcam --size 1920x1080 -o lens-stmap.exr\n";

namespace {

std::string joined(const std::vector<std::string>& parts, const char* separator) {
  std::string out;
  for (const std::string& part : parts) out += (out.empty() ? "" : separator) + part;
  return out;
}

}  // namespace

int exportMapCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--size", "", true},
                         {"--convention", "", true},
                         {"--source-size", "", true},
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
  // The maps are held whole before they are written (source_maps.h).
  if (static_cast<long long>(size.width) * size.height > kMaxSourceMapPixels)
    throw UsageError("--size " + *size_text + " is too large for a map (at most 2^27 pixels)");
  const std::string convention_name = args.valueOr("--convention", "stmap");
  const auto convention = stmapConventionFromName(convention_name);
  if (!convention)
    throw UsageError("--convention expects stmap or opencv, not \"" + convention_name + "\"");
  checkOutputs(args, {*output}, {path});
  // The camera's "-" is read as text (readArtcam); the map's "-" is an EXR spooled to stdout.
  StdioPaths streams(args, "", *output, "exr");

  const auto camera = readArtcam(path);
  if (!camera) throw CommandError(camera.status.message);
  for (const std::string& warning : cameraWarnings(*camera))
    std::fprintf(stderr, "artcam export-map: warning: %s: %s\n", path.c_str(), warning.c_str());
  if (camera->layers.size() > 1 && static_cast<long long>(size.width) * size.height *
                                           static_cast<long long>(camera->layers.size()) >
                                       kMaxSourceMapPixels)
    throw UsageError("--size " + *size_text + " is too large for a map of " +
                     std::to_string(camera->layers.size()) + " layers (at most 2^27 pixels in all)");
  SourceMapsOptions map_options;
  if (const auto source_text = args.value("--source-size"))
    map_options.source_px = parseSize(*source_text, "--source-size");
  const auto maps = sourceMaps(*camera, size, map_options);
  if (!maps) throw CommandError(path + ": " + maps.status.message);
  // Written, not refused: an ST map moves pixels and a compositor grades apart from it, so the
  // distortion is what a Nuke user asks export-map for; what it leaves out is named.
  if (!maps->left_out.empty())
    std::fprintf(stderr,
                 "artcam export-map: warning: %s: the map carries positions only; left out: %s "
                 "(artcam warp applies them, a warp through the map does not)\n",
                 path.c_str(), joined(maps->left_out, ", ").c_str());
  std::vector<StmapLayer> layers;
  std::vector<std::string> names;
  long long invalid = 0;
  for (const SourceMapLayer& layer : maps->layers) {
    layers.push_back({layer.name, &layer.map});
    if (!layer.name.empty()) names.push_back(layer.name);
    invalid = std::max(invalid, layer.map.invalid_pixels);
  }
  streams.open();
  if (const Status s = writeStmap(streams.output(), layers, *convention); !s)
    throw CommandError(streams.named(s.message));
  streams.sendOutput();
  const long long transparent = maps->transparentPixels();
  if (args.has("--json")) {
    const nlohmann::json j = {{"output", *output},
                              {"width", size.width},
                              {"height", size.height},
                              {"convention", std::string(stmapConventionName(*convention))},
                              {"kernel", maps->kernel},
                              {"layers", names},
                              {"invalid_pixels", invalid},
                              {"transparent_pixels", transparent},
                              {"left_out", maps->left_out}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    const std::string what =
        names.empty() ? "map" : std::to_string(names.size()) + " maps (" + joined(names, ", ") + ")";
    std::printf(
        "%s %s %dx%d (%s), %lld pixels without a preimage, %lld that read nothing "
        "(transparent in artcam warp)\nwrote %s\n",
        std::string(stmapConventionName(*convention)).c_str(), what.c_str(), size.width,
        size.height, maps->kernel.c_str(), invalid, transparent, streams.outputName().c_str());
  }
  return 0;
}

}  // namespace artcam::cli
