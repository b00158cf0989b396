// SPDX-License-Identifier: Apache-2.0
// artcam fit --flat-field: a flat-field photo → the camera that corrects its vignetting
// (core/lens/vignetting.h). Parses, reads the photo as the sensor's raster, calls core, prints
// the fit's error.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/orientation.h"
#include "core/lens/vignetting.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace artcam::cli {

int fitFlatFieldCommand(const Args& args, const std::string& flat_path) {
  for (const char* option : {"--stmap", "--lines", "--piecewise", "--dim", "--block", "--srgb",
                             "--robust", "--threshold", "--no-refine", "--allow-poles",
                             "--max-error", "--size", "--target-size", "--model", "--layer"})
    if (args.has(option))
      throw UsageError(std::string(option) +
                       " does not apply to --flat-field (the photo is the "
                       "data and its size the camera's)");
  if (!args.positional().empty())
    throw UsageError("unexpected argument " + args.positional()[0] +
                     ": with --flat-field the photo is the data");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o CAM.artcam");
  checkOutputs(args, {*output}, {flat_path});
  FlatFieldOptions options;
  options.cells = intOption(args, "--cells", options.cells, 4, 512);

  return runJobStages("fit", args.has("--quiet"), [&](JobStages& job) {
    job.stage("reading");
    auto read = readImage(flat_path);
    if (!read) throw CommandError(read.status.message);
    // Vignetting is the lens's, on the sensor's raster: a portrait flat field is turned back.
    ImageF flat = std::move(read->image);
    const int orientation = validOrientation(read->info.stored_orientation);
    if (orientation != 1) {
      const bool swap = orientationSwapsAxes(orientation);
      ImageF stored(swap ? flat.height : flat.width, swap ? flat.width : flat.height, flat.channels,
                    flat.alpha_channel);
      reorientPixels(flat.data.data(), flat.width, flat.height, sizeof(float) * flat.channels,
                     inverseOrientation(orientation), stored.data.data());
      flat = std::move(stored);
    }
    job.stage("fitting");
    const FlatFieldSummary fit = fitFlatField(flat, options);
    if (!fit.fit.status) throw CommandError(flat_path + ": " + fit.fit.status.message);

    job.stage("writing");
    Artcam doc(fit.camera);
    doc.frame = CameraFrame::Sensor;
    if (const Status s = writeArtcam(*output, doc); !s) throw CommandError(s.message);
    job.finish();

    const RadialGain& g = fit.fit.gain;
    if (args.has("--json")) {
      const nlohmann::json j = {{"flat_field", flat_path},
                                {"size", {flat.width, flat.height}},
                                {"cells", fit.fit.checked},
                                {"centre_px", {g.centre_px.x(), g.centre_px.y()}},
                                {"darkest", fit.darkest},
                                {"rational", fit.fit.rational},
                                {"max_percent", fit.fit.max_percent},
                                {"rms_percent", fit.fit.rms_percent},
                                {"output", *output}};
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    std::printf("%s: %dx%d, darkest %.1f%% of the axis (%.2f EV), axis at (%.1f, %.1f) px\n",
                flat_path.c_str(), flat.width, flat.height, 100.0 * fit.darkest,
                -std::log2(fit.darkest), g.centre_px.x(), g.centre_px.y());
    std::printf("vignetting gain against the flat field's cells: %s\n", fit.fit.report().c_str());
    std::printf("wrote %s\n", outputName(*output).c_str());
    return 0;
  });
}

}  // namespace artcam::cli
