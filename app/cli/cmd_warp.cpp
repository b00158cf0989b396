// artcam warp: image → image through a position camera (gather warp, DESIGN §3).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/warp_attributed.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/piecewise_file.h"
#include "core/io/stored_image.h"
#include "core/piecewise/piecewise_render.h"
#include "core/render/warp.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

namespace artcam::cli {
namespace {

int warpPiecewise(const PiecewiseCamera& camera, const std::string& input, const std::string& output,
                  const WarpOptions& options, bool stats) {
  if (options.width != 0 || options.height != 0)
    throw UsageError("--size does not apply to piecewise cameras (they render on their target frame)");
  const auto image = readImage(input);
  if (!image) throw CommandError(image.status.message);
  const auto start = std::chrono::steady_clock::now();
  const ImageF warped = renderPiecewise(image->image, camera);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (const Status s = writeImage(output, warped, &image->info); !s) throw CommandError(s.message);
  if (stats)
    std::fprintf(stderr, "render_ms=%.3f mpix_per_s=%.2f\n", ms,
                 ms > 0 ? warped.width * double(warped.height) / 1e3 / ms : 0.0);
  std::printf("wrote %s (%dx%d, piecewise mesh warp, %zu patches)\n", output.c_str(), warped.width,
              warped.height, camera.patches.size());
  return 0;
}

}  // namespace

const char* const kWarpUsage =
    "usage: artcam warp IN CAM.artcam -o OUT [--size WxH] [--filter nearest|bilinear|bicubic]\n"
    "                   [--threads N] [--stats] [--force]\n"
    "                   [--depth FILE [--depth-scale S] [--disparity BF]]\n\n"
    "Warps IN through the camera into OUT (format from OUT's extension, via OpenImageIO).\n"
    "The output has the camera's target frame size scaled by IN's size over the camera's\n"
    "source frame (a camera made on a preview applies to the full photo), or --size.\n"
    "Pixels with no preimage are transparent (an alpha channel is added where the format has\n"
    "one; else they are black).\n"
    "OUT keeps IN's pixel type and metadata. Where OUT's format stores IN's kind of sample\n"
    "(8/16-bit into PNG/JPEG/TIFF, float into EXR/TIFF) the warp reads and writes the stored\n"
    "values in place (no float copy: peak memory about input + output), interpolating them in\n"
    "the file's own encoding as OpenCV's remap does; otherwise it renders in linear float.\n"
    "OUT is written atomically; it may not be IN\n"
    "unless --force is given. --stats prints render_ms=<ms> mpix_per_s=<Mpix/s> on stderr\n"
    "(the render alone, without file I/O).\n"
    "A piecewise camera (artcam fit --piecewise) is rendered by its seamless mesh warp on its\n"
    "target frame.\n"
    "Cameras that change colour or depth, layered cameras (chromatic aberration) and depth of\n"
    "field go to the attributed renderer; those that read depth need --depth FILE: float\n"
    "EXR/TIFF as stored, integer files times --depth-scale S, or disparity made depth as\n"
    "BF / disparity with --disparity BF.\n";

int warpCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--size", "", true},
                         {"--filter", "", true},
                         {"--threads", "", true},
                         {"--stats", "", false},
                         {"--force", "", false},
                         {"--depth", "", true},
                         {"--depth-scale", "", true},
                         {"--disparity", "", true}});
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
  const Camera& camera = doc->camera;
  // Output size: the camera may have been made on a preview, so its target frame scales by
  // the ratio between this photo and the source frame it was made for (normalised frames make
  // that exact).
  const auto sizeFor = [&](int input_width) {
    if (options.width != 0 || options.height != 0 || !camera.sourceSize().isImage()) return;
    const double scale = static_cast<double>(input_width) / camera.sourceSize().width;
    options.width = std::max(1, static_cast<int>(std::lround(camera.targetSize().width * scale)));
    options.height = std::max(1, static_cast<int>(std::lround(camera.targetSize().height * scale)));
  };
  // Colour/depth cameras, layers and depth of field go to the attributed renderer (issue 6).
  const auto effect = readArtcamEffectFile(args.positional()[1]);
  if (!effect) throw CommandError(effect.status.message);
  if (needsAttributedWarp(*effect)) {
    const auto image = readImage(input);
    if (!image) throw CommandError(image.status.message);
    sizeFor(image->image.width);
    AttributedWarpRequest request{*output, args.value("--depth"), 1.0, 0.0, options, args.has("--stats")};
    try {
      request.depth_scale = std::stod(args.valueOr("--depth-scale", "1"));
      request.baseline_focal = std::stod(args.valueOr("--disparity", "0"));
    } catch (const std::exception&) {
      throw UsageError("--depth-scale and --disparity expect numbers");
    }
    return warpAttributed(*effect, *image, request);
  }
  // Piecewise cameras (issue 8): the mesh warp, never the top-level single camera alone.
  if (const auto pieces = readPiecewiseFile(args.positional()[1]); pieces && pieces->pieces)
    return warpPiecewise(*pieces->pieces, input, *output, options, args.has("--stats"));
  WarpSummary summary;
  int out_width = 0, out_height = 0;
  // The stored-type path (issue 5: peak memory ≤ input + output + a small constant).
  auto stored = readStoredImage(input);
  if (!stored) throw CommandError(stored.status.message);
  if (storedWriteKeepsEncoding(*output, stored->type)) {
    sizeFor(stored->width);
    const FrameSize out_size = warpOutputSize(camera, options);
    const bool add_alpha = stored->alpha_channel < 0 && formatStoresAlpha(*output);
    StoredImage warped = makeStoredImage(
        out_size.width, out_size.height, stored->channels + (add_alpha ? 1 : 0),
        add_alpha ? stored->channels : stored->alpha_channel, stored->type);
    warpImage(std::as_const(*stored).view(), camera, warped.view(), options, &summary);
    if (const Status s = writeStoredImage(*output, std::as_const(warped).view(), &stored->info); !s)
      throw CommandError(s.message);
    out_width = warped.width;
    out_height = warped.height;
  } else {
    // Re-encoding between integer and float files goes through linear light (image_io.h).
    stored = {};
    const auto image = readImage(input);
    if (!image) throw CommandError(image.status.message);
    sizeFor(image->image.width);
    const ImageF warped = warpImage(image->image, camera, options, &summary);
    if (const Status s = writeImage(*output, warped, &image->info); !s) throw CommandError(s.message);
    out_width = warped.width;
    out_height = warped.height;
  }
  if (args.has("--stats")) {
    const double mpix = static_cast<double>(out_width) * out_height / 1e6;
    std::fprintf(stderr, "render_ms=%.3f mpix_per_s=%.2f\n", summary.render_ms,
                 summary.render_ms > 0 ? mpix / (summary.render_ms / 1000.0) : 0.0);
  }
  std::printf("wrote %s (%dx%d, kernel %s, %lld transparent pixels)\n", output->c_str(),
              out_width, out_height, summary.kernel.c_str(), summary.transparent_pixels);
  return 0;
}

}  // namespace artcam::cli
