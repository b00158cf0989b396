// SPDX-License-Identifier: Apache-2.0
// artcam render: a point cloud through a 3D ARTcam, then a projecting view camera, into an
// image (z-buffered splats) or, with -o *.ply, the moved cloud itself.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/memory.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "core/cloud/cloud_render.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/ply.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <vector>

namespace artcam::cli {

const char* const kRenderUsage =
    "usage: artcam render CLOUD.ply CAM.artcam -o OUT.png|OUT.ply [--view VIEW.artcam]\n"
    "                     [--eye X,Y,Z] [--at X,Y,Z] [--fov DEGREES] [--size WxH]\n"
    "                     [--layers whole|rgb] [--point-size H] [--splat-scale S]\n"
    "                     [--threads N] [--stats] [--json] [--overwrite]\n\n"
    "Moves every point of CLOUD (and its colour) through CAM, an object-space ARTcam (a 3D\n"
    "preset such as twist-3d, or a camera fitted with artcam fit --dim 3; `artcam preset identity`\n"
    "for none). With -o OUT.ply the moved cloud is written. Otherwise it is seen through the\n"
    "view camera and splatted into OUT (any image format; transparent background):\n"
    "  --view VIEW.artcam  a projecting camera (artcam preset pinhole|orthographic|pushbroom|\n"
    "                      xslit|glc|rational-lens);\n"
    "  else a pinhole at --eye looking at --at (default: from (4, 3, -5) towards the centre of\n"
    "  CLOUD's bounds at 2.8 bounding radii, y up), with --fov across the larger image side\n"
    "  or, by default, a focal that frames the moved cloud.\n"
    "--size defaults to 512x512. --layers rgb renders the red, green and blue layers apart (the\n"
    "paper's chromatic aberration). Splats cover --splat-scale (0.75) times the image of one\n"
    "point spacing (--point-size, default: the median nearest-neighbour distance).\n"
    "--stats prints points, render_ms and points_per_s on stderr (render only, no file I/O).\n"
    "--json prints one JSON object on stdout instead of the \"wrote\" line: {output, points,\n"
    "dropped} for a cloud; {output, width, height, points, drawn, dropped, render_ms,\n"
    "points_per_s} for an image.\n"
    "--threads N sets the worker threads (default 0: all cores). -o/--output names OUT\n"
    "(required; written atomically; an existing OUT is refused unless --overwrite, --force\n"
    "being the same, and OUT is never CLOUD or a camera). -q/--quiet shows no progress bar\n"
    "(drawn on stderr only when it is a terminal).\n\n"
    "Examples:\n"
    "  artcam preset cube-of-cubes -o cube.ply && artcam preset twist-3d -o twist.artcam\n"
    "  artcam render cube.ply twist.artcam -o twisted.png --size 800x600 --eye 3,2,-4\n";

namespace {

// One message for a wrong count and a wrong number alike.
std::optional<Eigen::Vector3d> vectorOption(const Args& args, const std::string& option) {
  const auto text = args.value(option);
  if (!text) return std::nullopt;
  const UsageError refused(option + " expects X,Y,Z, got \"" + *text + "\"");
  std::vector<double> v;
  try {
    v = parseNumberList(*text, option, -kUnbounded, kUnbounded);
  } catch (const UsageError&) {
    throw refused;
  }
  if (v.size() != 3) throw refused;
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

Camera readObjectCamera(const std::string& path) {
  auto doc = readArtcam(path);
  if (!doc) throw CommandError(doc.status.message);
  if (doc->layers.size() != 1 || doc->pieces)
    throw CommandError(path + ": a " + std::string(artcamKindName(doc->kind())) +
                       " camera cannot view a point cloud (one object-space camera is needed)");
  const BlockLayout& l = doc->main().layout();
  const int p = l.find(BlockKind::Position);
  if (p < 0 || l.blocks[p].size != 4)
    throw CommandError(path +
                       ": not an object-space camera (its position block must have 4 "
                       "elements, X Y Z 1; image cameras are for artcam warp)");
  return doc->main();
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() &&
         std::equal(tail.rbegin(), tail.rend(), s.rbegin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

}  // namespace

int renderCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--view", "", true},
                         {"--eye", "", true},
                         {"--at", "", true},
                         {"--fov", "", true},
                         {"--size", "", true},
                         {"--layers", "", true},
                         {"--point-size", "", true},
                         {"--splat-scale", "", true},
                         {"--threads", "", true},
                         {"--stats", "", false},
                         {"--json", "", false},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--quiet", "-q", false}});
  args.expectPositional(2, "CLOUD.ply and CAM.artcam");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  std::vector<std::string> inputs = args.positional();
  if (const auto view = args.value("--view")) inputs.push_back(*view);
  checkOutputs(args, {*output}, inputs);

  CloudRenderOptions options;
  if (args.has("--size")) {
    const FrameSize size = parseSize(*args.value("--size"), "--size");
    checkImageMemory(size, "--size");
    options.width = size.width;
    options.height = size.height;
  }
  const std::string layers = args.valueOr("--layers", "whole");
  if (layers == "rgb")
    options.layers = RenderLayers::Rgb;
  else if (layers != "whole")
    throw UsageError("--layers expects whole or rgb");
  options.point_spacing =
      numberOption(args, "--point-size", options.point_spacing, 0, kUnbounded, Ends::OpenMin);
  options.splat_scale =
      numberOption(args, "--splat-scale", options.splat_scale, 0, kUnbounded, Ends::OpenMin);
  options.threads = intOption(args, "--threads", options.threads, 0, kMaxThreads);
  if (args.has("--view") && (args.has("--eye") || args.has("--at") || args.has("--fov")))
    throw UsageError("--view replaces --eye, --at and --fov");
  // The view's numbers are refused before the cloud is read; their defaults come from it.
  const std::optional<Eigen::Vector3d> eye_asked = vectorOption(args, "--eye");
  const std::optional<Eigen::Vector3d> at_asked = vectorOption(args, "--at");
  std::optional<double> fov;
  if (const auto text = args.value("--fov")) fov = parseNumber(*text, "--fov", 0, 180, Ends::Open);

  return runJobStages("render", args.has("--quiet"), [&](JobStages& job) {
    job.stage("reading");
    const auto cloud = readPly(args.positional()[0]);
    if (!cloud) throw CommandError(cloud.status.message);
    const std::vector<Camera> effects = {readObjectCamera(args.positional()[1])};

    if (endsWith(*output, ".ply")) {
      size_t dropped = 0;
      job.stage("moving points");
      const PointCloud moved = applyCameras(*cloud, effects, options.threads, &dropped);
      job.stage("writing");
      if (const Status s = writePly(*output, moved); !s) throw CommandError(s.message);
      job.finish();
      if (args.has("--json")) {
        const nlohmann::json j = {
            {"output", *output}, {"points", moved.size()}, {"dropped", dropped}};
        std::printf("%s\n", j.dump().c_str());
        return 0;
      }
      std::printf("wrote %s (%zu points, %zu dropped where the camera does not map)\n",
                  output->c_str(), moved.size(), dropped);
      return 0;
    }

    Camera view;
    if (args.has("--view")) {
      view = readObjectCamera(*args.value("--view"));
    } else {
      const CloudBounds bounds = cloudBounds(*cloud);
      const CameraPose fallback = defaultViewPose(bounds);
      const Eigen::Vector3d at =
          at_asked.value_or(bounds.empty ? Eigen::Vector3d::Zero() : bounds.centre());
      const Eigen::Vector3d eye = eye_asked.value_or(at + (fallback.centre - bounds.centre()));
      CameraPose pose;
      try {
        pose = CameraPose::lookAt(eye, at);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--eye/--at: ") + e.what());
      }
      PinholeParams pin;
      if (fov) {
        pin.focal = 1.0 / std::tan(*fov * std::numbers::pi / 360.0);
        pin.pose = pose;
      } else {
        job.stage("framing");
        pin = framingPinhole(applyCameras(*cloud, effects, options.threads), pose, options.width,
                             options.height);
      }
      view = pinholeCamera(pin);
    }

    // renderCloud and writeImage poll: Ctrl-C cancels them (an empty image, no file left).
    CloudRenderSummary summary;
    options.progress = job.polled("rendering");
    const ImageF image = renderCloud(*cloud, effects, view, options, &summary);
    job.check();
    WriteImageOptions write;
    write.progress = job.polled("writing");
    if (const Status s = writeImage(*output, image, nullptr, write); !s)
      throw CommandError(s.message);
    job.finish();
    if (args.has("--json")) {
      const nlohmann::json j = {{"output", *output},
                                {"width", image.width},
                                {"height", image.height},
                                {"points", summary.points},
                                {"drawn", summary.drawn},
                                {"dropped", summary.dropped},
                                {"render_ms", summary.render_ms},
                                {"points_per_s", summary.pointsPerSecond()}};
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    if (args.has("--stats"))
      std::fprintf(stderr, "points=%zu render_ms=%.1f points_per_s=%.0f\n", summary.points,
                   summary.render_ms, summary.pointsPerSecond());
    std::printf("wrote %s (%dx%d, %zu points drawn, %zu dropped)\n", output->c_str(), image.width,
                image.height, summary.drawn, summary.dropped);
    return 0;
  });
}

}  // namespace artcam::cli
