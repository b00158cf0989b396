// SPDX-License-Identifier: Apache-2.0
// artcam fit --piecewise: one camera per patch, split until every patch's max error is under
// --max-error (core/piecewise/piecewise_fit.h).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/fit_input.h"
#include "app/cli/progress.h"
#include "core/fit/fit_image.h"
#include "core/io/artcam_file.h"
#include "core/piecewise/piecewise_fit.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace artcam::cli {

int fitPiecewiseCommand(const Args& args, const std::string& output, FrameSize source,
                        FrameSize target, const MatchInput& input) {
  if (args.has("--robust") || args.has("--allow-poles"))
    throw UsageError("--robust and --allow-poles do not apply to --piecewise");
  PiecewiseOptions options;
  options.max_error_px =
      numberOption(args, "--max-error", options.max_error_px, 0, kUnbounded, Ends::OpenMin);
  if (args.has("--model")) {
    const auto model = modelClassFromName(*args.value("--model"));
    if (!model) throw UsageError("unknown --model \"" + *args.value("--model") + "\"");
    options.model = *model;
  }
  options.refine = !args.has("--no-refine");

  // Nothing here has a progress hook in core: the bar names the stage, and Ctrl-C exits at once
  // (the atomic writer's temporary is removed by the handler, interrupt.h).
  return runJobStages("fit", args.has("--quiet"), [&](JobStages& job) {
    const std::string& csv = input.name;
    job.stage("reading");
    const std::vector<PointMatch> matches = input.read();
    job.stage("fitting patches");
    const PiecewiseSummary fit = fitPiecewise(matches, source, target, options);
    if (!fit.status) throw CommandError(csv + ": " + fit.status.message);

    // The file's top level is the best single camera, so plain readers still get one; when no
    // pole-free single camera exists, the largest patch's camera stands in.
    job.stage("fitting the single camera");
    FitOptions single_options;
    single_options.diagnostics = false;
    const FitSummary single = fitImageCamera(matches, source, target, single_options);
    Artcam doc(single.status ? single.camera : fit.camera.patches.front().camera);
    doc.matches = matches;
    if (single.status) doc.fit = single.record;
    doc.pieces = fit.camera;
    job.stage("writing");
    if (const Status s = writeArtcam(output, doc); !s) throw CommandError(s.message);
    job.finish();
    // A patch that maps wholly outside the target frame is valid (coverage.h): written, and said.
    for (const std::string& warning : cameraWarnings(doc))
      std::fprintf(stderr, "artcam fit: warning: %s: %s\n", output.c_str(), warning.c_str());
    if (args.has("--json")) {
      nlohmann::json patches = nlohmann::json::array();
      for (const CameraPatch& p : fit.camera.patches)
        patches.push_back({{"rect", {p.rect.x0, p.rect.y0, p.rect.x1, p.rect.y1}},
                           {"model", p.model},
                           {"matches", p.matches},
                           {"rms_px", p.rms_px},
                           {"max_px", p.max_px},
                           // -1: no fold could be fitted (JSON has no infinity)
                           {"held_out_max_px", std::isfinite(p.held_out_max_px) ? p.held_out_max_px : -1.0},
                           {"within_tolerance", p.within_tolerance}});
      nlohmann::json j = {{"piecewise", true},
                          {"patches", fit.camera.patches.size()},
                          {"matches", fit.matches},
                          {"rms_px", fit.rms_px},
                          {"max_px", fit.max_px},
                          {"held_out_max_px", fit.held_out_max_px},
                          {"seam_gap_px", fit.seam_gap_px},
                          {"converged", fit.converged},
                          {"max_error_px", options.max_error_px},
                          {"patch_list", patches},
                          {"output", output}};
      // Negative in the summary when the single-camera fit failed: absent here.
      if (fit.single_rms_px >= 0) j["single_rms_px"] = fit.single_rms_px;
      if (fit.single_max_px >= 0) j["single_max_px"] = fit.single_max_px;
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    std::printf("%s\n", fit.report().c_str());
    for (size_t i = 0; i < fit.camera.patches.size(); ++i) {
      const CameraPatch& p = fit.camera.patches[i];
      char held[48];
      if (p.held_out_max_px < 0) std::snprintf(held, sizeof held, "not measured");
      else if (!std::isfinite(p.held_out_max_px)) std::snprintf(held, sizeof held, "unmeasurable");
      else std::snprintf(held, sizeof held, "%.3g px", p.held_out_max_px);
      std::printf(
          "  patch %zu [%.1f, %.1f]-[%.1f, %.1f] %s: %d matches, RMS %.3g px, max %.3g px, "
          "held-out max %s%s\n",
          i, p.rect.x0, p.rect.y0, p.rect.x1, p.rect.y1, p.model.c_str(), p.matches, p.rms_px,
          p.max_px, held, p.within_tolerance ? "" : " (above the threshold)");
    }
    return 0;
  });
}

}  // namespace artcam::cli
