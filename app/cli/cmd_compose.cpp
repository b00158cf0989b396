// artcam compose: one camera from a sequence of cameras (DESIGN §1 chains; paper §5).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "core/io/artcam_file.h"
#include "core/model/compose.h"
#include "core/model/structure.h"

#include <cstdio>

namespace artcam::cli {

const char* const kComposeUsage =
    "usage: artcam compose FIRST.artcam SECOND.artcam [MORE.artcam…] -o OUT.artcam\n\n"
    "Writes the camera that applies FIRST, then SECOND, and so on: OUT(x) = SECOND(FIRST(x)).\n"
    "The target pixels of each camera are the source pixels of the next (frame sizes may\n"
    "differ; the change of normalised frame is folded in).\n\n"
    "A homography on either side collapses into its neighbour, so e.g. a canonical view →\n"
    "table homography → reflection ARTcam becomes one single-stage camera. Two general\n"
    "rational cameras become a two-stage chain, which `artcam warp` renders exactly.\n\n"
    "options:\n"
    "  -o, --output FILE   the composed camera (written atomically)\n"
    "  --overwrite         replace OUT if it exists (--force is the same); never an input\n\n"
    "Example:\n"
    "  artcam compose view-to-table.artcam reflection.artcam -o view-to-reflection.artcam\n";

int composeCommand(const std::vector<std::string>& argv) {
  const Args args(argv,
                  {{"--output", "-o", true}, {"--overwrite", "", false}, {"--force", "", false}});
  const std::vector<std::string>& inputs = args.positional();
  if (inputs.size() < 2) throw UsageError("compose needs at least two camera files");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT.artcam");
  checkOutputs(args, {*output}, inputs);

  auto first = readArtcamFile(inputs[0]);
  if (!first) throw CommandError(first.status.message);
  Camera composed = first->camera;
  for (size_t i = 1; i < inputs.size(); ++i) {
    const auto next = readArtcamFile(inputs[i]);
    if (!next) throw CommandError(next.status.message);
    CompositionSummary summary;
    auto c = composeCameras(composed, next->camera, &summary);
    if (!c) throw CommandError(inputs[i] + ": cannot follow " + inputs[i - 1] + ": " + c.status.message);
    composed = std::move(*c);
    std::printf("%s: %s\n", inputs[i].c_str(), summary.description.c_str());
  }
  // No matches or fit record: the composed camera was not fitted to anything.
  const ArtcamDocument doc{composed, {}, std::nullopt};
  if (const Status s = writeArtcamFile(*output, doc); !s) throw CommandError(s.message);
  std::printf("wrote %s: %s\n", output->c_str(), analyseStructure(composed).summary.c_str());
  return 0;
}

}  // namespace artcam::cli
