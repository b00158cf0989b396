// SPDX-License-Identifier: Apache-2.0
#include "app/cli/warp_job.h"

#include "app/cli/commands.h"
#include "app/cli/memory.h"
#include "core/depth/depth_raster.h"
#include "core/effects/finish.h"
#include "core/io/depth_file.h"
#include "core/model/frames.h"
#include "core/pipeline/camera_frame.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>
#include <utility>

namespace artcam::cli {
namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

CommandError outOfMemory(const std::string& output, FrameSize size, int channels, PixelType type) {
  const double gib = static_cast<double>(size.width) * size.height * channels * pixelTypeSize(type) /
                     (1024.0 * 1024.0 * 1024.0);
  char amount[32];
  std::snprintf(amount, sizeof amount, "%.2f", gib);
  return CommandError(output + ": cannot write: not enough memory for " +
                      sizeText(size.width, size.height) + " (" + amount + " GiB)");
}

// The output keeps the photo's channels: the alpha the renderer adds is dropped again where the
// photo had none and every pixel has a preimage.
void dropAddedAlpha(StoredImage& image, bool input_had_alpha) {
  if (input_had_alpha || image.alpha_channel < 0) return;
  const int channels = dropOpaqueAlpha(image.view());
  if (channels == image.channels) return;
  image.channels = channels;
  image.alpha_channel = -1;
}

// Reads the input's extra channels where the output keeps them warped, else records why not.
void readOrLeaveOutExtra(const WarpCameraFile& camera, DecodedInput& decoded,
                         const ReadImageOptions& read) {
  const ImageInfo& info = decoded.stored ? decoded.stored->info : decoded.loaded->info;
  if (info.dropped_channels.empty() && info.other_parts.empty()) return;
  std::string reason = extraChannelsUnsupported(camera.camera);
  if (!reason.empty())
    reason = camera.path + ": " + reason;
  else if (!formatStoresExtraChannels(decoded.output))
    reason = "its format holds no channels beyond RGBA (OpenEXR does)";
  if (reason.empty() && !info.other_parts.empty()) {
    auto parts = readOtherParts(decoded.input, info, read);
    if (!parts) throw CommandError(parts.status.message);
    decoded.parts = std::move(*parts.value);
  }
  if (!reason.empty()) decoded.left_out_reason = reason;  // said for the parts too
  if (info.dropped_channels.empty()) return;
  if (!reason.empty()) {
    decoded.left_out = info.dropped_channels;
    decoded.left_out_reason = reason;
    return;
  }
  auto extra = readExtraChannels(decoded.input, info, read);  // the first part's
  if (!extra) throw CommandError(extra.status.message);
  decoded.extra = std::move(*extra.value);
}

// Each group of extra channels through the same render entry point as the image, into the
// image's output size: same camera, same source positions. Depth- and ID-like groups take the
// nearest filter (isDepthChannel, sampledNearest say why); the others the image's.
ExtraChannels renderExtra(const WarpCameraFile& camera, ExtraChannels&& source, int width,
                          int height, int turn, const RenderOptions& image_options,
                          double& render_ms) {
  ExtraChannels warped;
  for (ChannelGroup& group : source.groups) {
    RenderOptions options = image_options;
    if (group.nearest) {
      options.warp.filter = Filter::Nearest;
      options.warp.antialias = false;
    }
    ChannelGroup out{group.names, ImageF(width, height, group.image.channels, -1), group.depth,
                     group.nearest, group.stored_types};
    RenderInputs inputs;
    inputs.photo = viewOf(std::as_const(group.image));
    RenderSummary summary;
    renderTurned(inputs, camera.camera, options, turn, viewOf(out.image), &summary);
    if (summary.cancelled) return {};
    render_ms += summary.render_ms;
    group.image = ImageF();  // the input group is no longer needed
    warped.groups.push_back(std::move(out));
  }
  return warped;
}

// An OpenEXR plate whose data window is not its display window (overscan): the camera, made for
// the display window, re-expressed for the data window's pixels (reframeToRegions), so the
// output holds the same data window of the camera's output frame. Empty for any other input.
std::optional<WarpCameraFile> forDataWindow(const WarpCameraFile& camera,
                                            const DecodedInput& source,
                                            const WarpRequest& request) {
  if (!source.loaded) return std::nullopt;
  const ImageInfo& info = source.loaded->info;
  const ImageF& image = source.loaded->image;
  if (info.display_width <= 0 ||
      (info.data_origin_x == 0 && info.data_origin_y == 0 && info.display_width == image.width &&
       info.display_height == image.height))
    return std::nullopt;
  const std::string what =
      source.input + ": its data window (" + sizeText(image.width, image.height) + " at " +
      std::to_string(info.data_origin_x) + ", " + std::to_string(info.data_origin_y) +
      ") is not its display window (" + sizeText(info.display_width, info.display_height) + ")";
  if (camera.camera.isPiecewise())
    throw CommandError(what + ", and " + camera.path +
                       " is piecewise: its patches lie on the display window");
  if (camera.camera.sourceSize().width * camera.camera.targetSize().height !=
      camera.camera.sourceSize().height * camera.camera.targetSize().width)
    throw CommandError(what + ", and " + camera.path +
                       "'s output frame is not of the input frame's aspect");
  if (request.options.warp.width > 0 || request.depth || request.second)
    throw CommandError(what + ": --size, --depth and --second take display-window images");
  WarpCameraFile reframed = camera;
  const FrameSize display{info.display_width, info.display_height};
  const FrameSize data{image.width, image.height};
  for (Camera& layer : reframed.camera.layers) {
    layer.setFrames(display, display);
    reframeToRegions(layer, info.data_origin_x, info.data_origin_y, data, info.data_origin_x,
                     info.data_origin_y, data);
  }
  return reframed;
}

}  // namespace

std::string leftOutWarning(const RenderedOutput& output, const std::string& input_name,
                           const std::string& output_name) {
  std::string names, parts;
  for (const std::string& c : output.left_out) names += (names.empty() ? "" : ", ") + c;
  if (!output.parts_written)
    for (const std::string& p : output.like.other_parts)
      parts += (parts.empty() ? "\"" : ", \"") + p + "\"";
  std::string line;
  if (!names.empty())
    line = "channels beyond colour and alpha (" + names + ") are not warped and are left out of " +
           output_name + ": " + output.left_out_reason;
  // The readers hand over a multi-part OpenEXR's first part (image_io.h, ImageInfo::other_parts).
  if (!parts.empty())
    line += (line.empty() ? "" : "; ") + std::string("the parts after the first (") + parts +
            ") are not warped and are left out of " + output_name +
            (output.left_out_reason.empty() ? std::string() : ": " + output.left_out_reason);
  return line.empty() ? "" : input_name + ": " + line;
}

std::string droppedProfileWarning(const RenderedOutput& output, const std::string& input_name,
                                  const std::string& output_name) {
  if (output.like.profile_dropped.empty()) return "";
  return input_name + ": " + output.like.profile_dropped + ": not applied, and " + output_name +
         " carries no profile";
}

WarpRequest parseWarpRequest(const Args& args) {
  WarpRequest request;
  WarpOptions& warp = request.options.warp;
  const std::string filter_name = args.valueOr("--filter", "bilinear");
  const auto filter = filterFromName(filter_name);
  if (!filter) throw UsageError("unknown --filter \"" + filter_name + "\"");
  warp.filter = *filter;
  warp.edge = parseEdgeOption(args);
  if (args.has("--size")) {
    const FrameSize size = parseSize(*args.value("--size"), "--size");
    checkImageMemory(size, "--size");
    warp.width = size.width;
    warp.height = size.height;
  }
  warp.threads = intOption(args, "--threads", warp.threads, 0, kMaxThreads);
  // The depth reader's own ranges (depth_file.h): a scale above 0, a disparity factor ≥ 0 (0:
  // the file holds depth).
  DepthFileOptions depth;
  depth.scale = numberOption(args, "--depth-scale", depth.scale, 0, kUnbounded, Ends::OpenMin);
  depth.baseline_focal = numberOption(args, "--disparity", depth.baseline_focal, 0, kUnbounded);
  parseWriteOptions(args, request.write);  // every usage error before a file is read
  request.colour_space_in = parseColourSpaceIn(args);
  request.stats = args.has("--stats");
  if (const auto finish = parseFinishOption(args)) request.finish = *finish;
  // Nothing is printed here: the files read are reported with the result (WarpRequest::inputs),
  // so standard output carries only the image or the one JSON object.
  if (const auto path = args.value("--depth")) {
    DepthFileSummary summary;
    auto read = readDepthFile(*path, depth, &summary);
    if (!read) throw CommandError(read.status.message);
    request.depth = std::move(*read);
    // A depth map is one channel; an RGB render of depth, or depth with alpha, is read from its
    // first channel, and a user should know the others were left out.
    if (summary.channels > 1)
      std::fprintf(stderr, "warning: %s: %d channels; depth is read from the first channel only\n",
                   path->c_str(), summary.channels);
    request.inputs.push_back(
        {"depth", *path, request.depth->width, request.depth->height,
         RequestInput::DepthRange{summary.min_depth, summary.max_depth, summary.holes}});
  }
  if (const auto path = args.value("--second")) {
    auto second = readImage(*path);
    if (!second) throw CommandError(second.status.message);
    request.second = std::move(second->image);
    request.inputs.push_back(
        {"second", *path, request.second->width, request.second->height, std::nullopt});
  }
  return request;
}

std::string RequestInput::describe() const {
  char line[160];
  if (depth)
    std::snprintf(line, sizeof line, ": %dx%d, %g..%g, %lld holes", width, height, depth->min,
                  depth->max, depth->holes);
  else
    std::snprintf(line, sizeof line, ": %dx%d", width, height);
  return (role == "second" ? "second image " : role + " ") + path + line;
}

WarpCameraFile loadWarpCamera(const std::string& path) {
  auto camera = readArtcam(path);
  if (!camera) throw CommandError(camera.status.message);
  // A pole that takes part of the frame renders, with that part transparent: said once, here.
  for (const std::string& warning : cameraWarnings(*camera))
    std::fprintf(stderr, "warning: %s: %s\n", path.c_str(), warning.c_str());
  WarpCameraFile file{path, std::move(*camera), false};
  file.linear = needsLinearPhoto(file.camera);
  return file;
}

double DecodedInput::megapixels() const {
  if (stored) return static_cast<double>(stored->width) * stored->height / 1e6;
  if (streamed) return static_cast<double>(streamed->width()) * streamed->height() / 1e6;
  if (loaded) return static_cast<double>(loaded->image.width) * loaded->image.height / 1e6;
  return 0.0;
}

DecodedInput decodeForWarp(const WarpCameraFile& camera, const WarpRequest& request,
                           const std::string& input, const std::string& output,
                           const Progress& progress) {
  DecodedInput decoded;
  decoded.input = input;
  decoded.output = output;
  ReadImageOptions read;
  read.progress = progress;
  read.colour_space = request.colour_space_in;
  read.data_window = true;  // an overscan plate is kept (renderForWarp re-expresses the camera)
  // The stored-type path where the output keeps the input's encoding (peak memory ≤ input +
  // output + a small constant); re-encoding between integer and float files, and cameras that
  // render from the linear photo, go through linear light (image_io.h); so does
  // --colourspace srgb, which may re-encode an ICC-tagged input.
  // Named OpenColorIO colour spaces convert, so they go through linear light too.
  if (!camera.linear && request.write.colour_space == WriteImageOptions::ColourSpace::Input &&
      request.colour_space_in.empty() && request.write.ocio_colour_space.empty()) {
    const auto shape = readStoredShape(input);
    if (!shape) throw CommandError(shape.status.message);
    const PixelType type = shape->type;
    const std::string& asked = request.write.pixel_type;
    const bool same_type = asked.empty() || (asked == "uint8" && type == PixelType::UInt8) ||
                           (asked == "uint16" && type == PixelType::UInt16);
    // Values in other primaries (an ACEScg EXR) keep them only where the output names them.
    const bool primaries_kept = !shape->foreign_primaries || formatStoresExtraChannels(output);
    if (same_type && primaries_kept && !shape->data_window &&
        storedWriteKeepsEncoding(output, type)) {
      // The decoded photo and the output together (the output frame as the rule gives it, an
      // EXIF turn aside), and the float copy readStoredImage also checks, against the budget.
      const FrameSize out = outputFrameFor(camera.camera, {shape->width, shape->height},
                                           request.options.warp.width, request.options.warp.height).size;
      const double sample = pixelTypeSize(type);
      const double whole =
          static_cast<double>(shape->width) * shape->height * shape->channels * sample +
          static_cast<double>(out.width) * out.height * (shape->channels + 1) * sample;
      const double as_float = static_cast<double>(shape->width) * shape->height *
                              std::max(4, shape->channels) * 4.0;
      const double budget = memoryBudgetBytes();
      if ((whole > budget || as_float > budget) && streamableCamera(camera.camera)) {
        auto reader = StoredImageReader::open(input);
        if (!reader) throw CommandError(reader.status.message);
        decoded.streamed = std::move(*reader.value);
        // Bands carry colour and alpha only: the rest are named, never dropped silently.
        decoded.left_out = decoded.streamed->info().dropped_channels;
        decoded.left_out_reason =
            "the photo is warped in bands (too big for the memory budget "
            "whole), which carries colour and alpha only";
        return decoded;
      }
      auto stored = readStoredImage(input, read);
      if (!stored) throw CommandError(stored.status.message);
      decoded.stored = std::move(*stored.value);
      readOrLeaveOutExtra(camera, decoded, read);
      return decoded;
    }
  }
  auto loaded = readImage(input, read);
  if (!loaded) throw CommandError(loaded.status.message);
  decoded.loaded = std::move(*loaded.value);
  readOrLeaveOutExtra(camera, decoded, read);
  return decoded;
}

RenderedOutput renderForWarp(const WarpCameraFile& given, DecodedInput&& input,
                             const WarpRequest& request, const Progress& progress) {
  DecodedInput source = std::move(input);  // freed on return, before the output is encoded
  const std::optional<WarpCameraFile> reframed = forDataWindow(given, source, request);
  const WarpCameraFile& camera = reframed ? *reframed : given;
  RenderedOutput out;
  out.output = source.output;
  if (source.streamed && !request.finish.empty())
    throw CommandError(source.input + ": too big to hold whole for the " + request.finish +
                       " finish (it marks the whole picture at once)");
  if (source.streamed) {  // rendered band by band as encodeWarp writes
    out.like = source.streamed->info();
    out.streamed = std::move(source.streamed);
    out.left_out = std::move(source.left_out);
    out.left_out_reason = std::move(source.left_out_reason);
    return out;
  }
  RenderOptions options = request.options;
  options.warp.progress = progress;
  const ImageF* depth = request.depth ? &*request.depth : nullptr;
  RenderSummary summary;
  // The camera's frame (camera_frame.h): a camera made for the stored raster corrects it before
  // the EXIF turn.
  const ImageInfo& info = source.stored ? source.stored->info : source.loaded->info;
  const FrameSize upright =
      source.stored ? FrameSize{source.stored->width, source.stored->height}
                    : FrameSize{source.loaded->image.width, source.loaded->image.height};
  const int turn = turnAfterCamera(camera.camera, upright, info.stored_orientation);
  try {
    if (source.stored) {
      const StoredImage& in = *source.stored;
      const OutputFrame frame =
          outputFrameTurned(camera.camera, upright, turn, options.warp.width, options.warp.height);
      const bool add_alpha = in.alpha_channel < 0 && formatStoresAlpha(out.output);
      const int channels = in.channels + (add_alpha ? 1 : 0);
      // Uninitialised: the render writes every output pixel (warp.h), so the render's threads
      // fault the pages in, in parallel, instead of this one zeroing 72 MB first.
      try {
        out.stored = makeStoredImage(frame.size.width, frame.size.height, channels,
                                     add_alpha ? in.channels : in.alpha_channel, in.type,
                                     PixelBuffer::Init::Uninitialised);
      } catch (const std::bad_alloc&) {
        throw outOfMemory(out.output, frame.size, channels, in.type);
      }
      RenderInputs inputs;
      inputs.photo = in.view();
      inputs.depth = depth;
      renderTurned(inputs, camera.camera, options, turn, out.stored->view(), &summary);
      if (!summary.cancelled) dropAddedAlpha(*out.stored, in.alpha_channel >= 0);
      out.like = in.info;
      out.width = frame.size.width;
      out.height = frame.size.height;
      out.warning = frame.warning;
    } else {
      const LoadedImage& in = *source.loaded;
      const StoredEncoding encoding = storedEncodingOf(in.info);
      RenderInputs inputs = RenderInputs::of(in.image, depth, &encoding);
      if (request.second) inputs.second = &*request.second;
      ImageF image = renderTurned(inputs, camera.camera, options, turn, &summary);
      if (!summary.cancelled) {
        if (in.image.alpha_channel < 0) dropOpaqueAlpha(image);
        out.width = image.width;
        out.height = image.height;
        out.image = std::move(image);
      }
      out.like = in.info;
      out.warning =
          outputFrameTurned(camera.camera, upright, turn, options.warp.width, options.warp.height)
              .warning;
      // The second image lies over the photo's frame (core/pipeline/render.h): another size is
      // stretched to it, which a user should hear about.
      if (request.second)
        if (const std::string stretched = secondImageSizeNote(
                {request.second->width, request.second->height}, {in.image.width, in.image.height});
            !stretched.empty())
          out.warning += (out.warning.empty() ? "" : "; ") + stretched;
      if (depth)
        if (const std::string stretched = depthMapAspectNote({depth->width, depth->height},
                                                             {in.image.width, in.image.height});
            !stretched.empty())
          out.warning += (out.warning.empty() ? "" : "; ") + stretched;
    }
    // Marks after the render (core/effects/finish.h), on the values as they will be stored.
    if (!summary.cancelled && !request.finish.empty()) {
      Status marked;
      if (out.stored) {
        marked = applyFinish(out.stored->view(), request.finish);
      } else if (out.image) {
        marked = applyFinishLinear(*out.image, storedEncodingOf(out.like), request.finish);
      }
      if (!marked) throw CommandError(out.output + ": " + marked.message);
    }
    if (!summary.cancelled && !source.extra.empty()) {
      out.extra = renderExtra(camera, std::move(source.extra), out.width, out.height, turn, options,
                              summary.render_ms);
      out.extra_names = out.extra.names();
      summary.cancelled = out.extra.empty();
    }
    // Each later part through the same camera, as extra channels are (same source positions).
    for (ImagePart& part : source.parts) {
      if (summary.cancelled) break;
      ImagePart warped{part.name, renderExtra(camera, std::move(part.channels), out.width,
                                              out.height, turn, options, summary.render_ms)};
      summary.cancelled = warped.channels.empty();
      out.parts.push_back(std::move(warped));
    }
  } catch (const std::bad_alloc&) {
    throw CommandError(out.output + ": cannot render: not enough memory");
  } catch (const std::invalid_argument& e) {
    throw CommandError(camera.path + ": cannot render " + source.input + ": " + e.what());
  }
  if (summary.cancelled) throw CommandError(source.input + ": cancelled");
  out.left_out = std::move(source.left_out);
  out.left_out_reason = std::move(source.left_out_reason);
  out.render_ms = summary.render_ms;
  out.description = summary.describe();
  return out;
}

void encodeWarp(RenderedOutput& output, const WarpRequest& request, const Progress& progress,
                const WarpCameraFile& camera) {
  if (output.streamed) {
    StreamedWarpOptions streamed;
    streamed.warp = request.options.warp;
    streamed.warp.progress = progress;
    streamed.write = request.write;
    StreamedWarpSummary summary;
    const Status s = streamWarp(*output.streamed, camera.camera, output.output, streamed, &summary);
    output.streamed.reset();
    if (!s) throw CommandError(s.message);
    output.width = summary.size.width;
    output.height = summary.size.height;
    output.render_ms = summary.ms;
    output.description = summary.describe();
    output.warning = summary.warning;
    return;
  }
  WriteImageOptions options = request.write;
  options.progress = progress;
  if (!output.extra.empty()) options.extra_channels = &output.extra;
  if (!output.parts.empty()) options.other_parts = &output.parts;
  const Status s = output.stored
                       ? writeStoredImage(output.output, std::as_const(*output.stored).view(),
                                          &output.like, options)
                       : writeImage(output.output, *output.image, &output.like, options);
  if (!s) throw CommandError(s.message);
  output.stored.reset();
  output.image.reset();
  output.extra = {};
  output.parts_written = !output.parts.empty();
  output.parts = {};
}

}  // namespace artcam::cli
