// artcam warp: image → image through a position camera (gather warp, DESIGN §3).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/render/warp.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace artcam::cli {

const char* const kWarpUsage =
    "usage: artcam warp IN CAM.artcam -o OUT [--size WxH] [--filter nearest|bilinear|bicubic]\n"
    "                   [--threads N] [--stats] [--force]\n\n"
    "Warps IN through the camera into OUT (format from OUT's extension, via OpenImageIO).\n"
    "The output has the camera's target frame size scaled by IN's size over the camera's\n"
    "source frame (a camera made on a preview applies to the full photo), or --size.\n"
    "Pixels with no preimage are transparent (an alpha channel is added where the format has\n"
    "one; else they are black).\n"
    "OUT keeps IN's pixel type and metadata. OUT is written atomically; it may not be IN\n"
    "unless --force is given. --stats prints render_ms=<ms> mpix_per_s=<Mpix/s> on stderr\n"
    "(the render alone, without file I/O).\n";

int warpCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--size", "", true},
                         {"--filter", "", true},
                         {"--threads", "", true},
                         {"--stats", "", false},
                         {"--force", "", false}});
  args.expectPositional(2, "IN and CAM.artcam");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  const std::string& input = args.positional()[0];
  std::error_code ec;
  if (!args.has("--force") && std::filesystem::equivalent(input, *output, ec))
    throw CommandError(*output + ": refusing to overwrite the input image (use --force)");

  WarpOptions options;
  const std::string filter_name = args.valueOr("--filter", "bilinear");
  const auto filter = filterFromName(filter_name);
  if (!filter) throw UsageError("unknown --filter \"" + filter_name + "\"");
  options.filter = *filter;
  if (args.has("--size")) {
    const FrameSize size = parseSize(*args.value("--size"), "--size");
    options.width = size.width;
    options.height = size.height;
  }
  if (args.has("--threads")) {
    try {
      options.threads = std::stoi(*args.value("--threads"));
    } catch (const std::exception&) {
      throw UsageError("--threads expects a whole number");
    }
    if (options.threads < 0) throw UsageError("--threads expects a whole number ≥ 0");
  }

  const auto doc = readArtcamFile(args.positional()[1]);
  if (!doc) throw CommandError(doc.status.message);
  const auto image = readImage(input);
  if (!image) throw CommandError(image.status.message);

  if (options.width == 0 && options.height == 0 && doc->camera.sourceSize().isImage()) {
    // The camera may have been made on a preview: scale its target frame by the ratio between
    // this photo and the source frame it was made for (normalised frames make that exact).
    const double scale =
        static_cast<double>(image->image.width) / doc->camera.sourceSize().width;
    options.width = std::max(1, static_cast<int>(std::lround(doc->camera.targetSize().width * scale)));
    options.height = std::max(1, static_cast<int>(std::lround(doc->camera.targetSize().height * scale)));
  }
  WarpSummary summary;
  const ImageF warped = warpImage(image->image, doc->camera, options, &summary);
  if (const Status s = writeImage(*output, warped, &image->info); !s) throw CommandError(s.message);
  if (args.has("--stats")) {
    const double mpix = static_cast<double>(warped.width) * warped.height / 1e6;
    std::fprintf(stderr, "render_ms=%.3f mpix_per_s=%.2f\n", summary.render_ms,
                 summary.render_ms > 0 ? mpix / (summary.render_ms / 1000.0) : 0.0);
  }
  std::printf("wrote %s (%dx%d, kernel %s, %lld transparent pixels)\n", output->c_str(),
              warped.width, warped.height, summary.kernel.c_str(), summary.transparent_pixels);
  return 0;
}

}  // namespace artcam::cli
