#include "app/cli/warp_job.h"

#include "app/cli/commands.h"
#include "app/cli/warp_attributed.h"
#include "core/io/piecewise_file.h"
#include "core/piecewise/piecewise_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <new>
#include <system_error>
#include <utility>

namespace artcam::cli {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The camera may have been made on a preview, so its target frame scales by the ratio between
// this photo and the source frame it was made for (normalised frames make that exact).
WarpOptions optionsForInput(const Camera& camera, WarpOptions options, int input_width) {
  if (options.width != 0 || options.height != 0 || !camera.sourceSize().isImage()) return options;
  const double scale = static_cast<double>(input_width) / camera.sourceSize().width;
  options.width = std::max(1, static_cast<int>(std::lround(camera.targetSize().width * scale)));
  options.height = std::max(1, static_cast<int>(std::lround(camera.targetSize().height * scale)));
  return options;
}

std::string describe(const WarpSummary& summary) {
  return "kernel " + summary.kernel + ", " + std::to_string(summary.transparent_pixels) +
         " transparent pixels";
}

}  // namespace

WarpRequest parseWarpRequest(const Args& args) {
  WarpRequest request;
  const std::string filter_name = args.valueOr("--filter", "bilinear");
  const auto filter = filterFromName(filter_name);
  if (!filter) throw UsageError("unknown --filter \"" + filter_name + "\"");
  request.options.filter = *filter;
  if (args.has("--size")) {
    const FrameSize size = parseSize(*args.value("--size"), "--size");
    request.options.width = size.width;
    request.options.height = size.height;
  }
  if (args.has("--threads")) {
    try {
      request.options.threads = std::stoi(*args.value("--threads"));
    } catch (const std::exception&) {
      throw UsageError("--threads expects a whole number");
    }
    if (request.options.threads < 0) throw UsageError("--threads expects a whole number ≥ 0");
  }
  request.depth_path = args.value("--depth");
  try {
    request.depth_scale = std::stod(args.valueOr("--depth-scale", "1"));
    request.baseline_focal = std::stod(args.valueOr("--disparity", "0"));
  } catch (const std::exception&) {
    throw UsageError("--depth-scale and --disparity expect numbers");
  }
  request.stats = args.has("--stats");
  return request;
}

WarpCameraFile loadWarpCamera(const std::string& path) {
  WarpCameraFile file;
  file.path = path;
  auto effect = readArtcamEffectFile(path);
  if (!effect) throw CommandError(effect.status.message);
  file.effect = std::move(*effect);
  // Colour/depth cameras, layers and depth of field go to the attributed renderer (issue 6).
  file.attributed = needsAttributedWarp(file.effect);
  // Piecewise cameras (issue 8): the mesh warp, never the top-level single camera alone.
  if (!file.attributed)
    if (auto pieces = readPiecewiseFile(path); pieces && pieces->pieces)
      file.pieces = std::move(pieces->pieces);
  return file;
}

double DecodedInput::megapixels() const {
  if (stored) return static_cast<double>(stored->width) * stored->height / 1e6;
  if (loaded) return static_cast<double>(loaded->image.width) * loaded->image.height / 1e6;
  return 0.0;
}

DecodedInput decodeForWarp(const WarpCameraFile& camera, const std::string& input,
                           const std::string& output, const Progress& progress) {
  DecodedInput decoded{input, output, std::nullopt, std::nullopt};
  ReadImageOptions read;
  read.progress = progress;
  // The stored-type path where the output keeps the input's encoding (issue 5: peak memory
  // ≤ input + output + a small constant); re-encoding between integer and float files, and
  // the piecewise and attributed renderers, go through linear light (image_io.h).
  if (!camera.attributed && !camera.pieces) {
    const auto type = readStoredPixelType(input);
    if (!type) throw CommandError(type.status.message);
    if (storedWriteKeepsEncoding(output, *type)) {
      auto stored = readStoredImage(input, read);
      if (!stored) throw CommandError(stored.status.message);
      decoded.stored = std::move(*stored.value);
      return decoded;
    }
  }
  auto loaded = readImage(input, read);
  if (!loaded) throw CommandError(loaded.status.message);
  decoded.loaded = std::move(*loaded.value);
  return decoded;
}

RenderedOutput renderForWarp(const WarpCameraFile& camera, DecodedInput&& input,
                             const WarpRequest& request, const Progress& progress) {
  DecodedInput source = std::move(input);  // freed on return, before the output is encoded
  RenderedOutput out;
  out.output = source.output;
  const auto start = std::chrono::steady_clock::now();
  auto cancelled = [&] { return CommandError(source.input + ": cancelled"); };

  if (camera.attributed) {
    WarpOptions options =
        optionsForInput(camera.camera(), request.options, source.loaded->image.width);
    AttributedWarpRequest attributed{
        out.output, request.depth_path, request.depth_scale, request.baseline_focal,
        options,    request.stats};
    warpAttributed(camera.effect, *source.loaded, attributed);
    // The attributed renderer sizes its output by the same rule (warp.h outputSizeFor).
    const FrameSize size = outputSizeFor(camera.camera(), options.width, options.height);
    out.width = size.width;
    out.height = size.height;
    out.written = true;
    out.render_ms = millisecondsSince(start);
    out.description = "attributed renderer";
    return out;
  }
  if (camera.pieces) {
    if (request.options.width != 0 || request.options.height != 0)
      throw UsageError(
          "--size does not apply to piecewise cameras (they render on their target frame)");
    out.image = renderPiecewise(source.loaded->image, *camera.pieces);
    out.like = source.loaded->info;
    out.width = out.image->width;
    out.height = out.image->height;
    out.render_ms = millisecondsSince(start);
    out.description =
        "piecewise mesh warp, " + std::to_string(camera.pieces->patches.size()) + " patches";
    return out;
  }

  WarpSummary summary;
  if (source.stored) {
    const StoredImage& in = *source.stored;
    WarpOptions options = optionsForInput(camera.camera(), request.options, in.width);
    options.progress = progress;
    const FrameSize size = warpOutputSize(camera.camera(), options);
    const bool add_alpha = in.alpha_channel < 0 && formatStoresAlpha(out.output);
    try {
      out.stored = makeStoredImage(size.width, size.height, in.channels + (add_alpha ? 1 : 0),
                                   add_alpha ? in.channels : in.alpha_channel, in.type);
    } catch (const std::bad_alloc&) {
      throw CommandError(out.output + ": cannot write: not enough memory for " +
                         std::to_string(size.width) + "x" + std::to_string(size.height) +
                         " pixels");
    }
    warpImage(in.view(), camera.camera(), out.stored->view(), options, &summary);
    out.like = in.info;
    out.width = size.width;
    out.height = size.height;
  } else {
    WarpOptions options =
        optionsForInput(camera.camera(), request.options, source.loaded->image.width);
    options.progress = progress;
    out.image = warpImage(source.loaded->image, camera.camera(), options, &summary);
    out.like = source.loaded->info;
    if (!summary.cancelled) {
      out.width = out.image->width;
      out.height = out.image->height;
    }
  }
  if (summary.cancelled) throw cancelled();
  out.render_ms = summary.render_ms;
  out.description = describe(summary);
  return out;
}

void encodeWarp(RenderedOutput& output, const Progress& progress) {
  if (output.written) return;
  WriteImageOptions options;
  options.progress = progress;
  const Status s = output.stored
                       ? writeStoredImage(output.output, std::as_const(*output.stored).view(),
                                          &output.like, options)
                       : writeImage(output.output, *output.image, &output.like, options);
  if (!s) throw CommandError(s.message);
  output.stored.reset();
  output.image.reset();
}

bool sameFile(const std::string& input, const std::string& output) {
  std::error_code ec;
  return std::filesystem::equivalent(input, output, ec) && !ec;
}

}  // namespace artcam::cli
