// SPDX-License-Identifier: Apache-2.0
// artcam fit --lines: lens calibration from straight lines (core/fit/fit_lines.h), with point
// pairs when MATCHES.csv is given too. Parses, calls core, prints each line's remaining bow.
// Without --target-size the fit is the studio document's (fitDocumentLines,
// core/project/document_camera.h): the same lines give the studio's camera.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/fit_input.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/reports.h"
#include "app/cli/stdio_paths.h"
#include "core/fit/fit_lines.h"
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"
#include "core/project/document_camera.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace artcam::cli {

int fitLinesCommand(const Args& args, const std::string& lines_path) {
  for (const char* option : {"--stmap", "--piecewise", "--dim", "--block", "--srgb", "--robust",
                             "--threshold", "--no-refine", "--allow-poles", "--max-error"})
    if (args.has(option))
      throw UsageError(std::string(option) + " does not apply to --lines");
  if (args.positional().size() > 1)
    throw UsageError("unexpected argument " + args.positional()[1] +
                     ": --lines takes at most one MATCHES.csv beside it");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o CAM.artcam");
  const auto size_text = args.value("--size");
  if (!size_text) throw UsageError("missing --size WxH (the photo's size)");
  const FrameSize source = parseSize(*size_text, "--size");
  const FrameSize target =
      args.has("--target-size") ? parseSize(*args.value("--target-size"), "--target-size") : source;
  const std::string model_name = args.valueOr("--model", "auto");
  const auto model = lineModelFromName(model_name);
  if (!model)
    throw UsageError("--model with --lines expects auto, radial or quadratic, not \"" +
                     model_name + "\"");
  std::vector<std::string> inputs = {lines_path};
  if (!args.positional().empty()) inputs.push_back(args.positional()[0]);
  checkOutputs(args, {*output}, inputs);
  LinesFitOptions options;
  options.model = *model;
  checkFitOptions(options, {{"model", "--model"}});

  return runJobStages("fit", args.has("--quiet"), [&](JobStages& job) {
    job.stage("reading");
    const auto lines = readLinesCsv(lines_path);
    if (!lines) throw CommandError(lines.status.message);
    std::vector<PointMatch> pairs;
    if (!args.positional().empty()) {
      auto read = readMatchesCsv(args.positional()[0], 2);
      if (!read) throw CommandError(read.status.message);
      pairs = std::move(*read);
    }
    job.stage("fitting");
    // The studio's own line fit when the frames agree, so the two make the same camera.
    const LinesFitSummary fit = target == source
                                    ? fitDocumentLines(*lines, pairs, source, options.model)
                                    : fitLinesCamera(*lines, pairs, source, target, options);
    if (!fit.status) throw CommandError(lines_path + ": " + fit.status.message);

    job.stage("writing");
    Artcam doc(fit.camera);
    doc.matches = pairs;
    doc.fit = fit.record();
    if (const Status s = writeArtcam(*output, doc); !s) throw CommandError(s.message);
    job.finish();

    if (args.has("--json")) {
      nlohmann::json j = linesFitJson(fit);
      j["output"] = *output;
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    std::printf("%s\n", fit.report().c_str());
    std::printf("%s\n", fit.reason.c_str());
    for (size_t k = 0; k < fit.bows.size(); ++k)
      std::printf("line %s: %d points, bow %.3g px (before %.3g px)\n", fit.bows[k].label.c_str(),
                  fit.bows[k].points, fit.bows[k].max_px, fit.bows_before[k].max_px);
    std::printf("wrote %s\n", outputName(*output).c_str());
    return 0;
  });
}

}  // namespace artcam::cli
