// artcam map: source pixels → target pixels through a camera, exact to %.17g.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"

#include <cstdio>
#include <string>

namespace artcam::cli {

const char* const kMapUsage =
    "usage: artcam map CAM.artcam POINTS.csv\n\n"
    "Reads rows x,y (source pixels; a header line is allowed) and prints rows x,y,X,Y with\n"
    "the target pixels, numbers as %.17g. A point on the camera's pole curve (where it maps\n"
    "to infinity) is an error naming its row; nothing is printed then. No options.\n\n"
    "Example:\n"
    "  artcam map lens.artcam corners.csv > corners-mapped.csv\n";

int mapCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {});
  args.expectPositional(2, "CAM.artcam and POINTS.csv");
  const auto doc = readArtcamFile(args.positional()[0]);
  if (!doc) throw CommandError(doc.status.message);
  const Camera& camera = doc->camera;
  const auto& layout = camera.layout();
  if (layout.blocks.size() != 1 || layout.blocks[0].kind != BlockKind::Position ||
      layout.blocks[0].size != 3)
    throw CommandError(args.positional()[0] +
                       ": map needs a position-only image camera (its blocks carry colour or "
                       "depth, or it is 3D)");
  const auto points = readPointsCsv(args.positional()[1]);
  if (!points) throw CommandError(points.status.message);
  std::string out;
  char line[160];
  for (size_t k = 0; k < points->size(); ++k) {
    const Eigen::Vector2d& p = (*points)[k];
    const auto y = targetPixelFromSourcePixel(camera, p);
    if (!y)
      throw CommandError(args.positional()[1] + ": point " + std::to_string(k + 1) +
                         " lies on the camera's pole curve and has no image");
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g\n", p.x(), p.y(), y->x(), y->y());
    out += line;
  }
  std::fputs(out.c_str(), stdout);
  return 0;
}

}  // namespace artcam::cli
