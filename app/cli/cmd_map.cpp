// SPDX-License-Identifier: Apache-2.0
// artcam map: source pixels → target pixels through any camera, exact to %.17g.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"
#include "core/io/text_input.h"
#include "core/pipeline/point_map.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

namespace artcam::cli {

const char* const kMapUsage =
    "usage: artcam map CAM.artcam POINTS.csv [--json]\n\n"
    "Reads rows x,y (source pixels; a header line is allowed) and prints rows x,y,X,Y with\n"
    "the target pixels, numbers as %.17g. Every camera kind maps:\n"
    "  a piecewise camera through the patch that holds the point (as warp renders it);\n"
    "  a layered camera (chromatic aberration) prints one X,Y pair per layer:\n"
    "    x,y,X1,Y1,X2,Y2,…;\n"
    "  a camera with colour or depth blocks maps through its position part, when its\n"
    "    positions depend on position alone (otherwise map refuses: where a point goes\n"
    "    depends on its colour or depth).\n"
    "Every row is answered. A point with no image (on the camera's pole curve, where it maps\n"
    "to infinity, or outside every patch of a piecewise camera, where warp renders nothing) is\n"
    "printed with its X,Y fields empty (x,y,, ; null in --json), and a warning on stderr counts\n"
    "such rows and names the first.\n\n"
    "options:\n"
    "  --json    print {\"layers\": L, \"points\": [{\"source\": [x, y], \"target\": [[X, Y], …]}, …]}\n\n"
    "Example:\n"
    "  artcam map lens.artcam corners.csv > corners-mapped.csv\n";

int mapCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--json", "", false}});
  args.expectPositional(2, "CAM.artcam and POINTS.csv");
  checkStreamArguments(args, args.positional(), {});
  const std::string path = textInputName(args.positional()[0]);
  const auto camera = readArtcam(args.positional()[0]);
  if (!camera) throw CommandError(camera.status.message);
  const auto mapper = PointMapper::of(*camera, path);
  if (!mapper) throw CommandError(mapper.status.message);
  const auto points = readPointsCsv(args.positional()[1]);
  if (!points) throw CommandError(points.status.message);
  const bool json = args.has("--json");
  nlohmann::json rows = nlohmann::json::array();
  std::string out;
  char line[64];
  std::vector<size_t> unmapped;  // rows (from 1) with no image in some layer
  for (size_t k = 0; k < points->size(); ++k) {
    const Eigen::Vector2d& p = (*points)[k];
    std::snprintf(line, sizeof line, "%.17g,%.17g", p.x(), p.y());
    std::string text = line;
    nlohmann::json targets = nlohmann::json::array();
    for (size_t layer = 0; layer < mapper->layers(); ++layer) {
      const auto y = mapper->map(layer, p);
      if (!y) {  // a per-point flag, never a made-up number: empty fields, null in JSON
        if (unmapped.empty() || unmapped.back() != k + 1) unmapped.push_back(k + 1);
        text += ",,";
        targets.push_back(nullptr);
        continue;
      }
      std::snprintf(line, sizeof line, ",%.17g,%.17g", y->x(), y->y());
      text += line;
      targets.push_back({y->x(), y->y()});
    }
    out += text + "\n";
    rows.push_back({{"source", {p.x(), p.y()}}, {"target", std::move(targets)}});
  }
  if (!unmapped.empty()) {
    std::string rows_text;
    for (size_t i = 0; i < std::min<size_t>(unmapped.size(), 5); ++i)
      rows_text += (i ? ", " : "") + std::to_string(unmapped[i]);
    if (unmapped.size() > 5) rows_text += ", …";
    std::fprintf(stderr,
                 "artcam map: warning: %s: %zu of %zu points have no image (%s), their X,Y left "
                 "empty: row%s %s\n",
                 textInputName(args.positional()[1]).c_str(), unmapped.size(), points->size(),
                 camera->pieces ? "outside every patch, or on a patch's pole curve"
                                : "on the camera's pole curve",
                 unmapped.size() > 1 ? "s" : "", rows_text.c_str());
  }
  if (json) {
    const nlohmann::json doc = {{"camera", path}, {"layers", mapper->layers()}, {"points", rows}};
    std::printf("%s\n", doc.dump().c_str());
  } else {
    std::fputs(out.c_str(), stdout);
  }
  return 0;
}

}  // namespace artcam::cli
