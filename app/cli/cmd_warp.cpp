// SPDX-License-Identifier: Apache-2.0
// artcam warp: image → image through any camera (core/pipeline/render.h). The stages
// (decode, render, encode) are warp_job.h's, shared with artcam batch.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/stdio_paths.h"
#include "app/cli/warp_job.h"
#include "core/util/parallel.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace artcam::cli {

const char* const kWarpUsage =
    "usage: artcam warp IN CAM.artcam -o OUT [--size WxH] [--filter nearest|bilinear|bicubic]\n"
    "                   [--edge transparent|extend|black] [--format EXT] [--threads N]\n"
    "                   [--quality N] [--subsampling 444|422|420]\n"
    "                   [--bit-depth 8|16|half|float] [--colourspace input|srgb]\n"
    "                   [--colourspace-in NAME] [--colourspace-out NAME]\n"
    "                   [--stats] [--json] [--quiet] [--overwrite]\n"
    "                   [--depth FILE [--depth-scale S] [--disparity BF]]\n"
    "                   [--second FILE] [--finish pencil|charcoal|painting|cartoon]\n\n"
    "Warps IN through the camera into OUT (format from OUT's extension, via OpenImageIO).\n"
    "IN \"-\" reads the photo from standard input (any format, found from its bytes); OUT \"-\"\n"
    "writes the image to standard output in the format --format EXT names (png, jpg, exr,\n"
    "tif, ...), encoded in full before the first byte is sent, so a failure sends nothing.\n"
    "Standard output then carries only the image: reports go to stderr; --json is refused.\n"
    "Output frame: the camera's target frame scaled per axis by IN's size over the camera's\n"
    "source frame and rounded, so a camera made on a preview applies to the full photo and a\n"
    "camera of IN's own size and aspect keeps IN's exact size; if IN's aspect differs from the\n"
    "source frame's by more than a rounding pixel the result is stretched per axis and a\n"
    "warning names both sizes. --size WxH overrides the rule.\n"
    "Channels: IN's channels are kept; an alpha channel is added only where some pixel has no\n"
    "preimage (transparent; black in formats without alpha) or IN had alpha. Channels beyond\n"
    "RGBA (an EXR's Z, N.x, AOVs) are warped at the same source positions into an EXR OUT,\n"
    "names and types kept (depth and ID-like channels: *.id, *.index, crypto*, integers, by\n"
    "the nearest texel), every part of a multi-part EXR too; OUT in another format, or a\n"
    "camera that moves R, G, B apart or changes colour or depth, leaves them out with a\n"
    "warning. An EXR OUT keeps IN's display-window origin; an EXR IN whose data window is\n"
    "not its display window (overscan) keeps both windows (not with --size, --depth,\n"
    "--second or a piecewise camera).\n"
    "IN is read upright: an EXIF orientation (a portrait photo stored sideways) is applied\n"
    "first, and OUT is written upright with orientation 1. A camera made for the sensor's\n"
    "raster (lens cameras; one whose \"frame\" is \"sensor\", or an older file whose source\n"
    "frame has the stored raster's aspect and not the upright one's) corrects the stored\n"
    "pixels, and the result is turned upright after it.\n"
    "OUT keeps IN's pixel type (unless --bit-depth), JPEG quality (unless --quality) and\n"
    "metadata: EXIF, IPTC and the XMP packet as IN has them, with the pixel size updated and the\n"
    "EXIF thumbnail removed, Software naming artcam and IN's tool kept in the XMP history\n"
    "(xmpMM:History); HEIC and AVIF get EXIF and XMP too (IPTC has no place there), a JPEG\n"
    "IN's chroma subsampling, a 10/12-bit DPX its bits. Where OUT's format stores IN's kind\n"
    "of sample and --bit-depth\n"
    "does not change it (8/16-bit into PNG/JPEG/TIFF, float into EXR/TIFF) the warp reads and\n"
    "writes the stored values in place (no float copy: peak memory about input + output),\n"
    "interpolating them in the file's own encoding as OpenCV's remap does; otherwise it\n"
    "renders in linear float.\n"
    "Colour: IN is read into linear Rec.709/D65; an ICC profile other than sRGB is converted\n"
    "(lcms2) and, by default, 8/16-bit OUT is encoded back into it with it embedded.\n"
    "OUT is written atomically (Ctrl-C leaves no partial file; exit status 130). An OUT that\n"
    "exists is refused unless --overwrite; OUT is never IN, the camera or the depth file.\n"
    "--stats prints render_ms=<ms> mpix_per_s=<Mpix/s> threads=<N> on stderr (the render alone,\n"
    "without file I/O; N: --threads, else the CPUs of the process's affinity mask and cgroup\n"
    "cpu.max). --json prints one JSON object on stdout instead of the \"wrote\" line:\n"
    "{output, width, height, description}, with --stats also render_ms, mpix_per_s, threads; with\n"
    "--depth also depth {file, width, height, min, max, holes}, with --second second {file,\n"
    "width, height}.\n"
    "Every camera kind renders: a piecewise camera (artcam fit --piecewise) by its seamless\n"
    "mesh warp, layered and attributed cameras by the attributed renderer.\n"
    "Cameras that change colour or depth, layered cameras (chromatic aberration) and depth of\n"
    "field go to the attributed renderer; those that read depth need --depth FILE: float\n"
    "EXR/TIFF as stored, integer files times --depth-scale S, or disparity made depth as\n"
    "BF / disparity with --disparity BF.\n"
    "Compositing cameras (artcam preset composite) blend a second image with IN and need\n"
    "--second FILE: read as linear premultiplied colour over IN's frame (an image of another\n"
    "size is stretched to IN's, with a warning); IN is the photo A of \"A over B\".\n"
    "A photo whose decode and output would pass the memory budget (half the machine's memory,\n"
    "or ARTCAM_MAX_MEMORY_MB) is warped in bands, holding only the rows the coming bands read,\n"
    "when its camera is a plain position camera; the output is the same.\n\n"
    "options:\n"
    "  -o, --output OUT     the warped image (required); - for standard output\n"
    "  --format EXT         the image format for -o - (png, jpg, exr, tif, ...); refused with a\n"
    "                       file OUT, whose extension says the format\n"
    "  --size WxH           output size in pixels (default: the target frame scaled as above)\n"
    "  --filter NAME        nearest, bilinear or bicubic (default bilinear)\n"
    "  --edge MODE          what the filter reads past the edge: transparent (default: the\n"
    "                       last half pixel fades out; black in formats without alpha, as the\n"
    "                       ST maps of export-map assume), extend (the edge pixel, as Hugin's\n"
    "                       nona and fulla and OpenImageIO's clamp) or black (opaque black)\n"
    "  --threads N          worker threads (default 0: all cores)\n"
    "  --quality N          JPEG quality 1-100 (default: IN's when IN and OUT are JPEG, else\n"
    "                       95); HEIC/AVIF quality (default: the encoder's); PNG: zlib level\n"
    "                       N/10 (as ImageMagick), the pixels the same\n"
    "  --subsampling S      JPEG chroma subsampling 444, 422 or 420 (default: IN's when IN and\n"
    "                       OUT are JPEG, else 420)\n"
    "  --bit-depth B        8, 16, half or float, fitted to what OUT's format stores (default:\n"
    "                       IN's)\n"
    "  --colourspace C      input or srgb: what 8/16-bit output is encoded in (default input:\n"
    "                       IN's ICC profile when it had one, embedded; srgb: sRGB, with an\n"
    "                       sRGB profile). Float output is linear Rec.709/D65, but an OpenEXR\n"
    "                       output keeps an EXR input's other primaries (ACEScg) with input\n"
    "  --colourspace-in NAME the OpenColorIO colour space the input is in, over what the\n"
    "                       file says (config: $OCIO, else OpenImageIO's built-in one)\n"
    "  --colourspace-out NAME the OpenColorIO colour space the output is encoded in\n"
    "  --stats              print render_ms and mpix_per_s on stderr\n"
    "  --json               the result (and --stats) as one JSON object on stdout\n"
    "  --overwrite          replace OUT if it exists (--force is the same); never IN\n"
    "  -q, --quiet          no progress bar on stderr (shown only on a terminal)\n"
    "  --depth FILE         per-pixel depth for cameras that read it (no default)\n"
    "  --depth-scale S      multiplies an integer depth file's values (default 1)\n"
    "  --disparity BF       the depth file holds disparity; depth = BF / disparity (default:\n"
    "                       off, the file holds depth)\n"
    "  --second FILE        the second image for compositing cameras (no default)\n"
    "  --finish NAME        marks after the render (G'MIC): pencil, charcoal, painting or\n"
    "                       cartoon (default none)\n\n"
    "Examples:\n"
    "  artcam warp photo.jpg lens.artcam -o fixed.jpg\n"
    "  cat photo.jpg | artcam warp - lens.artcam -o - --format png | display -\n"
    "  artcam warp photo.png dof.artcam -o blurred.png --depth depth.exr --filter bicubic\n"
    "  artcam warp title.png over.artcam -o card.png --second backdrop.png\n"
    "  artcam warp photo.jpg fig5.artcam -o marked.jpg --finish pencil\n";

int warpCommand(const std::vector<std::string>& argv) {
  const Args args(
      argv,
      {{"--output", "-o", true},    {"--format", "", true},         {"--size", "", true},
       {"--filter", "", true},      {"--edge", "", true},           {"--threads", "", true},
       {"--quality", "", true},     {"--subsampling", "", true},    {"--bit-depth", "", true},
       {"--colourspace", "", true}, {"--colourspace-in", "", true}, {"--colourspace-out", "", true},
       {"--stats", "", false},      {"--json", "", false},          {"--overwrite", "", false},
       {"--force", "", false},      {"--quiet", "-q", false},       {"--depth", "", true},
       {"--depth-scale", "", true}, {"--disparity", "", true},      {"--second", "", true},
       {"--finish", "", true}});
  args.expectPositional(2, "IN and CAM.artcam");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  StdioPaths streams(args, args.positional()[0], *output);
  // Standard streams are no files: no output to refuse, no input to protect (checkOutputs
  // leaves "-" out), but only one input can be standard input.
  std::vector<std::string> inputs = {args.positional()[1], args.positional()[0]};
  if (const auto depth = args.value("--depth")) inputs.push_back(*depth);
  if (const auto second = args.value("--second")) inputs.push_back(*second);
  checkOutputs(args, {*output}, inputs);
  const WarpRequest request = parseWarpRequest(args);
  const WarpCameraFile camera = loadWarpCamera(args.positional()[1]);
  streams.open();
  const std::string& input = streams.inputName();
  const std::string& output_name = streams.outputName();
  // Reports never share standard output with the image.
  std::FILE* report = streams.outputIsStdout() ? stderr : stdout;

  // Ctrl-C stops between bands of rows; the atomic writer removes its temporary.
  const CooperativeInterrupt interrupt;
  ProgressBar bar(0, args.has("--quiet"));
  auto stage = [&](const char* name) {
    return cancelOnInterrupt([&bar, name](double done) { bar.stage(name, done); });
  };
  // The exit status says what is on disk: once encodeWarp has renamed the output into place the
  // job is done, and a signal that lands after that (while the summary is printed) no longer
  // makes it an interrupted run (exit 130 with the new output in place).
  bool written = false;
  try {
    DecodedInput decoded =
        decodeForWarp(camera, request, streams.input(), streams.output(), stage("reading"));
    RenderedOutput rendered = renderForWarp(camera, std::move(decoded), request, stage("warping"));
    encodeWarp(rendered, request, stage("writing"), camera);
    streams.sendOutput();
    written = true;
    bar.finish();
    const double mpix = static_cast<double>(rendered.width) * rendered.height / 1e6;
    const double mpix_per_s = rendered.render_ms > 0 ? mpix / (rendered.render_ms / 1000.0) : 0.0;
    if (!rendered.warning.empty())
      std::fprintf(stderr, "artcam warp: warning: %s\n", rendered.warning.c_str());
    // Channels past RGBA that are not warped are said, never dropped silently.
    if (const std::string left_out = leftOutWarning(rendered, input, output_name); !left_out.empty())
      std::fprintf(stderr, "artcam warp: warning: %s\n", left_out.c_str());
    if (const std::string profile = droppedProfileWarning(rendered, input, output_name);
        !profile.empty())
      std::fprintf(stderr, "artcam warp: warning: %s\n", profile.c_str());
    if (args.has("--json")) {
      nlohmann::json j = {{"output", *output},
                          {"width", rendered.width},
                          {"height", rendered.height},
                          {"description", rendered.description}};
      if (!rendered.warning.empty()) j["warning"] = rendered.warning;
      if (!rendered.left_out.empty()) j["dropped_channels"] = rendered.left_out;
      if (!rendered.extra_names.empty()) j["extra_channels"] = rendered.extra_names;
      for (const RequestInput& in : request.inputs) {
        nlohmann::json& o = j[in.role];
        o = {{"file", in.path}, {"width", in.width}, {"height", in.height}};
        if (in.depth) {
          o["min"] = in.depth->min;
          o["max"] = in.depth->max;
          o["holes"] = in.depth->holes;
        }
      }
      if (request.stats) {
        j["render_ms"] = rendered.render_ms;
        j["mpix_per_s"] = mpix_per_s;
        j["threads"] = resolveThreadCount(request.options.warp.threads);
      }
      std::printf("%s\n", j.dump().c_str());
    } else if (request.stats) {
      std::fprintf(stderr, "render_ms=%.3f mpix_per_s=%.2f threads=%d\n", rendered.render_ms,
                   mpix_per_s, resolveThreadCount(request.options.warp.threads));
    }
    if (!args.has("--json")) {
      for (const RequestInput& in : request.inputs)
        std::fprintf(report, "%s\n", in.describe().c_str());
      std::fprintf(report, "wrote %s (%dx%d, %s)\n", output_name.c_str(), rendered.width,
                   rendered.height, rendered.description.c_str());
    }
  } catch (const CommandError& e) {
    if (!interruptRequested()) throw CommandError(streams.named(e.what()));
  }
  bar.finish();
  if (interruptRequested() && !written) {
    std::fprintf(stderr, "artcam warp: interrupted; %s not written\n", output_name.c_str());
    return interruptExitCode();
  }
  return 0;
}

}  // namespace artcam::cli
