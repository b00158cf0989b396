// SPDX-License-Identifier: Apache-2.0
// artcam export: a saved studio project rendered headless, through the functions the studio's
// File ▸ Export uses (core/project/project_render.h), so the file is the one the studio writes.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/cli/memory.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/project_export.h"
#include "app/cli/write_args.h"

#include "core/io/artcam_file.h"
#include "core/io/stored_image.h"
#include "core/project/project_render.h"

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace artcam::cli {

const char* const kExportUsage =
    "usage: artcam export PROJECT.artcamproj -o OUT [--photo FILE] [--camera-out CAM.artcam]\n"
    "                     [--depth-out DEPTH.exr] [--size WxH] [--filter NAME] [--quality N]\n"
    "                     [--edge transparent|extend|black] [--subsampling 444|422|420]\n"
    "                     [--bit-depth 8|16|half|float] [--colourspace input|srgb]\n"
    "                     [--colourspace-in NAME] [--colourspace-out NAME]\n"
    "                     [--crop-valid | --fill R,G,B[,A]]\n"
    "                     [--finish pencil|charcoal|painting|cartoon|none]\n"
    "                     [--json] [--quiet] [--overwrite]\n\n"
    "Renders a project saved by ARTcam Studio at the photo's full resolution, exactly as the\n"
    "studio's File > Export Warped Image does: the camera fitted from the project's point pairs\n"
    "with its model (or the camera set by hand), the colour block of the Colour panel, then the\n"
    "effect stack in order, reading the depth of the painted planes and the depth map. An effect\n"
    "that cannot be applied (it reads depth and the project has none) is left out, and a warning\n"
    "on stderr says which and why, as the studio's status line does.\n"
    "OUT keeps the photo's pixel type and metadata unless --bit-depth says otherwise; it is\n"
    "written atomically, and an existing file is refused unless --overwrite. No output may be\n"
    "the project, its photo or its depth map.\n\n"
    "options:\n"
    "  -o, --output OUT       the rendered image (required)\n"
    "  --photo FILE           render FILE in place of the project's photo (the photo moved):\n"
    "                         it must have the size the project's pairs and masks were made on\n"
    "  --camera-out CAM       also write the whole camera it rendered with (.artcam)\n"
    "  --depth-out DEPTH      also write the depth it read: float EXR, one channel Z, depth per\n"
    "                         pixel, 0 where there is none (what artcam warp --depth reads)\n"
    "  --size WxH             output size in pixels (default: the photo's size; one side 0: by\n"
    "                         aspect)\n"
    "  --filter NAME          nearest, bilinear or bicubic (default bilinear, as artcam warp and\n"
    "                         the studio's canvas: the same camera gives the same pixels)\n"
    "  --edge MODE            what the filter reads past the photo's edge: transparent\n"
    "                         (default: the last half pixel fades out), extend (the edge\n"
    "                         pixel, as Hugin's fulla) or black (composited over black)\n"
    "  --quality N            JPEG quality 1-100 (default: the photo's when it is a JPEG,\n"
    "                         else 95)\n"
    "                         HEIC/AVIF quality (default: the encoder's); PNG: zlib level\n"
    "                         N/10 (as ImageMagick), the pixels the same\n"
    "  --subsampling S        JPEG chroma subsampling 444, 422 or 420 (default: the photo's\n"
    "                         when it is a JPEG, else 420)\n"
    "  --bit-depth B          8, 16, half or float (default: the photo's)\n"
    "  --colourspace C        input or srgb: what 8/16-bit OUT is encoded in (default input:\n"
    "                         the photo's ICC profile when it had one, embedded; srgb: sRGB,\n"
    "                         with an sRGB profile). Float OUT is linear Rec.709/D65, but an\n"
    "                         OpenEXR keeps an EXR photo's other primaries (ACEScg) with input\n"
    "  --colourspace-in NAME  the OpenColorIO colour space the photo is in, over what the file\n"
    "                         says (config: $OCIO, else OpenImageIO's built-in one)\n"
    "  --colourspace-out NAME the OpenColorIO colour space OUT is encoded in\n"
    "  --finish NAME          marks after the render (G'MIC), over the project's own finish\n"
    "                         (the studio's Effects > Finish); none: without it\n"
    "  --crop-valid           crop to the largest rectangle whose every pixel has a preimage\n"
    "  --fill R,G,B[,A]       linear colour under pixels without a preimage (default: none,\n"
    "                         they stay transparent; a JPEG, which has no alpha, is filled\n"
    "                         with white)\n"
    "  --json                 the result as one JSON object on stdout\n"
    "  --overwrite            replace existing outputs (--force is the same)\n"
    "  -q, --quiet            no progress bar on stderr (shown only on a terminal)\n\n"
    "Examples:\n"
    "  artcam export resources/depth-effects.artcamproj -o hazy.jpg --quality 92\n"
    "  artcam export trip.artcamproj --photo new-place/photo.jpg -o out.jpg\n"
    "  artcam export trip.artcamproj -o out.tif --bit-depth 16 --crop-valid \\\n"
    "      --camera-out trip.artcam --depth-out trip-depth.exr\n";

namespace {

// One message for a wrong count and a wrong number alike: it states both rules.
std::array<float, 4> parseFill(const std::string& text) {
  const UsageError refused("--fill expects 3 or 4 comma-separated numbers from 0 to 1, got \"" +
                           text + "\"");
  std::vector<double> v;
  try {
    v = parseNumberList(text, "--fill", 0.0, 1.0);
  } catch (const UsageError&) {
    throw refused;
  }
  if (v.size() != 3 && v.size() != 4) throw refused;
  const auto f = [&v](size_t k) { return static_cast<float>(v[k]); };
  return {f(0), f(1), f(2), v.size() == 4 ? f(3) : 1.0f};
}

}  // namespace

const std::vector<OptionSpec>& projectExportOptions() {
  static const std::vector<OptionSpec> options = {
      {"--photo", "", true},       {"--camera-out", "", true},     {"--depth-out", "", true},
      {"--size", "", true},        {"--filter", "", true},         {"--edge", "", true},
      {"--quality", "", true},     {"--subsampling", "", true},    {"--bit-depth", "", true},
      {"--colourspace", "", true}, {"--colourspace-in", "", true}, {"--colourspace-out", "", true},
      {"--crop-valid", "", false}, {"--fill", "", true},           {"--finish", "", true},
      {"--overwrite", "", false},  {"--force", "", false}};
  return options;
}

ProjectExport exportProject(const Args& args, const std::string& output,
                            const std::function<bool(double)>& render_progress,
                            const std::function<bool(double)>& write_progress,
                            const std::function<void(const std::string&)>& warn) {
  args.expectPositional(1, "PROJECT.artcamproj");
  ExportOptions options;
  if (const auto size = args.value("--size")) {
    const FrameSize s = parseSizeByAspect(*size, "--size");
    if (s.width > 0 && s.height > 0) checkImageMemory(s, "--size");
    options.width = s.width;
    options.height = s.height;
  }
  if (const auto filter_name = args.value("--filter")) {
    const auto filter = filterFromName(*filter_name);
    if (!filter) throw UsageError("unknown --filter \"" + *filter_name + "\"");
    options.filter = *filter;
  }
  parseWriteOptions(args, options.write);
  ReadImageOptions read;
  read.colour_space = parseColourSpaceIn(args);
  options.edge = parseEdgeOption(args);
  options.crop_to_valid = args.has("--crop-valid");
  if (const auto fill = args.value("--fill")) {
    if (options.crop_to_valid) throw UsageError("--crop-valid and --fill exclude each other");
    options.fill = parseFill(*fill);
  }
  options = exportOptionsForOutput(std::move(options), output);  // a JPEG is filled white
  const std::optional<std::string> finish = parseFinishOption(args, /*allow_none=*/true);

  const std::string& project_path = args.positional()[0];
  Result<StudioProject> project = readStudioProject(project_path);
  if (!project) throw CommandError(project.status.message);
  options.finish = finish.value_or(project->finish);
  if (const auto photo = args.value("--photo")) {
    // Checked from the header before anything is laid on it: another size would put the
    // pairs and masks on the wrong pixels.
    Result<StoredShape> shape = readStoredShape(*photo);
    if (!shape) throw CommandError(project_path + ": --photo: " + shape.status.message);
    if (const Status s =
            checkProjectPhotoSize(*project, {shape->width, shape->height}, *photo, project_path);
        !s)
      throw CommandError(s.message);
    project->photo_path = std::filesystem::absolute(*photo).string();
  }
  ProjectExport done;
  done.output = output;
  done.camera_out = args.value("--camera-out");
  done.depth_out = args.value("--depth-out");
  std::vector<std::string> outputs = {output};
  if (done.camera_out) outputs.push_back(*done.camera_out);
  if (done.depth_out) outputs.push_back(*done.depth_out);
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t k = i + 1; k < outputs.size(); ++k)
      if (outputs[i] == outputs[k] || isSameFile(outputs[i], outputs[k]))
        throw UsageError("two outputs name the same file: " + outputs[i]);
  std::vector<std::string> inputs = {project_path, project->photo_path};
  if (project->second_path) inputs.push_back(*project->second_path);
  if (project->depth_map) inputs.push_back(project->depth_map->path);
  checkOutputs(args, outputs, inputs);
  if (std::error_code ec;
      !args.value("--photo") && !std::filesystem::exists(project->photo_path, ec))
    throw CommandError(project_path + ": its photo " + project->photo_path +
                       " is missing (moved?); give its new place with --photo FILE");

  Result<ProjectScene> scene = loadProjectScene(*project, project_path, read);
  if (!scene) throw CommandError(scene.status.message);
  done.note = scene->camera.note;
  if (!done.note.empty() && warn) warn(done.note);
  if (done.depth_out && scene->depth.empty())
    throw CommandError(project_path + ": --depth-out: the project has no depth (no plane with "
                                      "three depths, no depth map)");
  const bool reads_depth = readsDepth(scene->camera.camera);
  ImageF out;
  try {
    out = renderExport(scene->photo, reads_depth ? &scene->depth : nullptr, scene->camera.camera,
                       options, render_progress, &done.summary, &scene->second);
  } catch (const std::invalid_argument& e) {
    throw CommandError(project_path + ": " + e.what());
  }
  // Asked once more at the end: a stop that came after the last tile writes nothing either.
  if (done.summary.cancelled || (render_progress && !render_progress(1.0))) {
    done.cancelled = true;
    return done;
  }
  options.write.progress = write_progress;
  if (const Status s = writeImage(output, out, &scene->photo.info, options.write); !s)
    throw CommandError(s.message);
  if (done.camera_out)
    if (const Status s = writeArtcam(*done.camera_out, scene->camera.camera); !s)
      throw CommandError(s.message);
  if (done.depth_out)
    if (const Status s = writeDepthMapFile(*done.depth_out, scene->depth); !s)
      throw CommandError(s.message);
  done.width = out.width;
  done.height = out.height;
  done.camera = std::move(scene->camera.camera);
  done.effects_applied = scene->camera.applied.size();
  done.effects = project->effects.size();
  return done;
}

nlohmann::json projectExportJson(const ProjectExport& done) {
  nlohmann::json j = {{"output", done.output},
                      {"width", done.width},
                      {"height", done.height},
                      {"description", done.summary.describe()},
                      {"render_ms", done.summary.render_ms},
                      {"camera", std::string(artcamKindName(done.camera.kind()))},
                      {"effects_applied", done.effects_applied},
                      {"effects", done.effects}};
  if (!done.note.empty()) j["warning"] = done.note;
  if (done.camera_out) j["camera_out"] = *done.camera_out;
  if (done.depth_out) j["depth_out"] = *done.depth_out;
  return j;
}

int exportCommand(const std::vector<std::string>& argv) {
  std::vector<OptionSpec> specs = projectExportOptions();
  specs.insert(specs.end(),
               {{"--output", "-o", true}, {"--json", "", false}, {"--quiet", "-q", false}});
  const Args args(argv, specs);
  args.expectPositional(1, "PROJECT.artcamproj");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  const CooperativeInterrupt interrupt;
  ProgressBar bar(0, args.has("--quiet"));
  const ProjectExport done = exportProject(
      args, *output, cancelOnInterrupt([&bar](double f) { bar.stage("rendering", f); }),
      cancelOnInterrupt([&bar](double f) { bar.stage("writing", f); }),
      [](const std::string& note) {
        std::fprintf(stderr, "artcam export: warning: %s\n", note.c_str());
      });
  bar.finish();
  if (done.cancelled || interruptRequested()) {
    std::fprintf(stderr, "artcam export: interrupted; %s not written\n", output->c_str());
    return interruptExitCode();
  }
  if (args.has("--json"))
    std::printf("%s\n", projectExportJson(done).dump().c_str());
  else
    std::printf("wrote %s (%dx%d, %s)\n", output->c_str(), done.width, done.height,
                done.summary.describe().c_str());
  return 0;
}

}  // namespace artcam::cli
