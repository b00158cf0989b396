// SPDX-License-Identifier: Apache-2.0
// artcam compose: one camera from a sequence of cameras (chains of stages; the paper's §5),
// layer by layer for layered cameras, patch by patch for a piecewise first camera.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/io/text_input.h"
#include "core/model/compose.h"
#include "core/model/structure.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace artcam::cli {

const char* const kComposeUsage =
    "usage: artcam compose FIRST.artcam SECOND.artcam [MORE.artcam…] -o OUT.artcam [--json]\n\n"
    "Writes the camera that applies FIRST, then SECOND, and so on: OUT(x) = SECOND(FIRST(x)).\n"
    "The target frame of each camera is the source frame of the next. A camera made for\n"
    "another size of the same shape is applied as warp applies a camera to a photo of another\n"
    "size (scaled, and the line for it says so); frames of different shapes are refused.\n\n"
    "A homography on either side collapses into its neighbour, so e.g. a canonical view →\n"
    "table homography → reflection ARTcam becomes one single-stage camera. Two general\n"
    "rational cameras become a two-stage chain, which `artcam warp` renders exactly.\n"
    "Layered cameras (chromatic aberration) compose layer by layer; a single camera composes\n"
    "with every layer. A piecewise camera composes patch by patch with a single image position\n"
    "camera after it, and with a homography before it (folded into every patch, exact: the\n"
    "paper's canonical view -> table -> reflection). Depth flows from one camera's depth\n"
    "output to the next one's depth input: composing is refused when the first outputs\n"
    "something else than a depth (aerial perspective's log depth, depth of field's blur\n"
    "variance) and the next reads depth, since the next would read the wrong quantity.\n\n"
    "options:\n"
    "  -o, --output FILE   the composed camera (written atomically)\n"
    "  --json              print {\"output\": …, \"kind\": …, \"structure\": …, \"steps\": […]}\n"
    "  --overwrite         replace an existing OUT (--force is the same); never an input\n\n"
    "Example:\n"
    "  artcam compose view-to-table.artcam reflection.artcam -o view-to-reflection.artcam\n";

int composeCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--force", "", false},
                         {"--overwrite", "", false},
                         {"--json", "", false}});
  const std::vector<std::string>& paths = args.positional();
  if (paths.size() < 2) throw UsageError("compose needs at least two camera files");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT.artcam");
  checkOutputs(args, {*output}, paths);
  // The names messages give: "<stdin>" for "-".
  std::vector<std::string> inputs;
  for (const std::string& path : paths) inputs.push_back(textInputName(path));

  auto first = readArtcam(paths[0]);
  if (!first) throw CommandError(first.status.message);
  Artcam composed = std::move(*first);
  const bool json = args.has("--json");
  nlohmann::json steps = nlohmann::json::array();
  for (size_t i = 1; i < inputs.size(); ++i) {
    const auto next = readArtcam(paths[i]);
    if (!next) throw CommandError(next.status.message);
    std::string description;
    auto c = composeArtcams(composed, *next, &description);
    if (!c) throw CommandError(inputs[i] + ": cannot follow " + inputs[i - 1] + ": " + c.status.message);
    composed = std::move(*c);
    steps.push_back({{"camera", inputs[i]}, {"description", description}});
    if (!json) std::printf("%s: %s\n", inputs[i].c_str(), description.c_str());
  }
  // Two usable cameras can compose into one that renders nothing (the second's pole across the
  // first's image): refused like such a file would be on read. One that only misses the target
  // frame is valid, and warned about below.
  if (const Status s = validateArtcam(composed); !s)
    throw CommandError(outputName(*output) + ": the composed camera is not usable: " + s.message);
  if (const Status s = writeArtcam(*output, composed); !s) throw CommandError(s.message);
  // One whose picture misses the target frame is valid (coverage.h): written, and said.
  for (const std::string& warning : cameraWarnings(composed))
    std::fprintf(stderr, "artcam compose: warning: %s: %s\n", outputName(*output).c_str(),
                 warning.c_str());
  const std::string summary = analyseStructure(composed.main()).summary;
  if (json)
    std::printf("%s\n", nlohmann::json{{"output", *output},
                                       {"kind", std::string(artcamKindName(composed.kind()))},
                                       {"layers", composed.layers.size()},
                                       {"structure", summary},
                                       {"steps", steps}}
                            .dump()
                            .c_str());
  else
    std::printf("wrote %s: %s camera, %s\n", outputName(*output).c_str(),
                std::string(artcamKindName(composed.kind())).c_str(), summary.c_str());
  return 0;
}

}  // namespace artcam::cli
