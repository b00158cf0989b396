// SPDX-License-Identifier: Apache-2.0
// What `artcam export` does between reading its arguments and printing its report: a saved
// studio project rendered at the photo's full resolution (core/project/project_render.h, the
// studio's own export) and written with its camera and depth when asked, every output checked
// first. The command and the Python module (artcam.export_project) both run it.
#pragma once

#include "app/cli/args.h"
#include "core/model/artcam.h"
#include "core/pipeline/render.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace artcam::cli {

// The options it reads: --photo, --camera-out, --depth-out, --size, --filter, --edge, the write
// options, --crop-valid, --fill, --finish, --overwrite/--force (not -o, --json, --quiet).
const std::vector<OptionSpec>& projectExportOptions();

struct ProjectExport {
  std::string output;
  std::optional<std::string> camera_out, depth_out;
  int width = 0, height = 0;
  RenderSummary summary;
  Artcam camera;     // the project's whole camera
  std::string note;  // what the camera leaves out or stretches ("" none)
  size_t effects_applied = 0, effects = 0;
  bool cancelled = false;  // a progress hook said stop: nothing was written
};

// `args`: the project file as its one positional and projectExportOptions(). `warn` hears the
// camera's note as soon as the project is read (before the render). Throws UsageError and
// CommandError with the command's messages.
ProjectExport exportProject(const Args& args, const std::string& output,
                            const std::function<bool(double)>& render_progress,
                            const std::function<bool(double)>& write_progress,
                            const std::function<void(const std::string&)>& warn);

// `artcam export --json`'s object.
nlohmann::json projectExportJson(const ProjectExport& done);

}  // namespace artcam::cli
