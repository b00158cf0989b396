// SPDX-License-Identifier: Apache-2.0
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/cli/memory.h"
#include "app/cli/terminal_text.h"
#include "core/io/standard_streams.h"
#include "core/util/memory_budget.h"

#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string_view>

namespace artcam::cli {
namespace {

const Command kCommands[] = {
    {"fit", "fit a camera to point matches (CSV)", kFitUsage, fitCommand},
    {"map", "map source pixels through a camera", kMapUsage, mapCommand},
    {"warp", "warp an image through a camera", kWarpUsage, warpCommand},
    {"batch", "warp many images or a frame sequence", kBatchUsage, batchCommand},
    {"info", "describe a camera file", kInfoUsage, infoCommand},
    {"bench", "time the render kernels (CSV, plot)", kBenchUsage, benchCommand},
    {"render", "render a point cloud through 3D and view cameras", kRenderUsage, renderCommand},
    {"preset", "write a preset camera or the sample cloud", kPresetUsage, presetCommand},
    {"compose", "one camera from a sequence of cameras", kComposeUsage, composeCommand},
    {"export", "render a saved studio project as the studio exports it", kExportUsage,
     exportCommand},
    {"export-map", "write a camera's inverse map as an ST map (Nuke, OpenCV)", kExportMapUsage,
     exportMapCommand},
    {"lens", "search the lensfun database; a camera that corrects a lens", kLensUsage, lensCommand},
    {"insert", "render a graphic into a reflection or refraction", kInsertUsage, insertCommand},
    {"sample", "ray trace a sample photo and grid matches for insert", kSampleUsage, sampleCommand},
    {"stereo", "a depth map from a rectified stereo pair", kStereoUsage, stereoCommand},
    {"unfold", "a camera that unfolds the walls of a building (Fig 2)", kUnfoldUsage,
     unfoldCommand},
};

void printHelp() {
  std::printf(
      "artcam — ARTcam Studio on the command line: fit, inspect and apply Attributed Rational\n"
      "Tensor cameras (every output coordinate a ratio of quadratic forms of the input).\n\n"
      "usage: artcam <command> [options]   (artcam <command> --help for details)\n\n"
      "commands:\n");
  for (const Command& c : kCommands) std::printf("  %-10s %s\n", c.name, c.summary);
  std::printf(
      "\nPixels: centres at i + 0.5, (0, 0) the top-left corner, y down. Cameras are stored\n"
      "in normalised frames, so a camera made on a preview applies to the full-size photo.\n"
      "Errors: one line on stderr naming the file, the place and the cause; exit status 1\n"
      "(2 for a usage error); no partial output file is ever left behind. An output that\n"
      "exists is replaced only with --overwrite (alias --force); an input never is. Sizes\n"
      "are WxH; commands that report print one JSON object with --json.\n\n"
      "options: -h, --help (this page), --version (print the version). The manual: man artcam.\n\n"
      "Example:\n"
      "  artcam fit matches.csv -o lens.artcam --size 6000x4000\n"
      "  artcam warp photo.jpg lens.artcam -o fixed.jpg\n");
}

// A usage error in at most three lines on stderr: what is wrong, the likely intended name
// if one is close, and where the full page is (never the page itself: it would bury the error).
void printUsageError(const std::string& who, const std::string& message, const std::string& hint,
                     const std::string& help_call) {
  std::fprintf(stderr, "%s: %s\n", who.c_str(), message.c_str());
  if (!hint.empty()) std::fprintf(stderr, "%s\n", hint.c_str());
  std::fprintf(stderr, "see '%s --help'\n", help_call.c_str());
}

int runCommand(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    printUsageError("artcam", "missing the command (usage: artcam <command> [options])", "",
                    "artcam");
    return 2;
  }
  // `artcam help CMD [SUB]` is `artcam CMD [SUB] --help`, as git and cargo read it.
  if (args[0] == "help" && args.size() > 1) {
    args.erase(args.begin());
    args.push_back("--help");
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    printHelp();
    return 0;
  }
  if (args[0] == "--version") {
    std::printf("artcam 0.1.0\n");
    return 0;
  }
  for (const Command& c : kCommands) {
    if (args[0] != c.name) continue;
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    for (const std::string& a : rest)
      if (a == "--help" || a == "-h") {
        // `bench effects` has its own page; `bench` and `bench fit` share the bench page.
        const bool effects = std::string_view(c.name) == "bench" && rest.front() == "effects";
        // `preset`'s page lists the effects table, so it is made, not a literal.
        const bool preset = std::string_view(c.name) == "preset";
        std::printf("%s", effects ? kBenchEffectsUsage : preset ? presetHelp().c_str() : c.usage);
        return 0;
      }
    // Ctrl-C/kill never leave a partial file (interrupt.h).
    installInterruptHandlers();
    // A budget the user meant to set but mistyped would silently be half the machine's memory.
    if (const std::string problem = memoryBudgetProblem(); !problem.empty()) {
      std::fprintf(stderr, "artcam %s: %s\n", c.name, problem.c_str());
      return 2;
    }
    try {
      return c.run(rest);
    } catch (const UsageError& e) {
      std::string page = std::string("artcam ") + c.name;
      if (page == "artcam bench" && !rest.empty() &&
          (rest.front() == "fit" || rest.front() == "effects"))
        page += " " + rest.front();
      printUsageError(std::string("artcam ") + c.name, e.what(), e.hint, page);
      return 2;
    } catch (const std::bad_alloc&) {
      // An allocation the budget checks did not foresee: the user's words, not the library's.
      std::fprintf(stderr, "artcam %s: %s\n", c.name, allocationFailureMessage().c_str());
      return 1;
    } catch (const std::length_error&) {  // "cannot create std::vector larger than max_size()"
      std::fprintf(stderr, "artcam %s: %s\n", c.name, allocationFailureMessage().c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "artcam %s: %s\n", c.name, e.what());
      return 1;
    }
  }
  std::vector<std::string> names = {"--help", "--version"};
  for (const Command& c : kCommands) names.push_back(c.name);
  printUsageError("artcam", "unknown command \"" + args[0] + "\"", didYouMean(args[0], names),
                  "artcam");
  return 2;
}

}  // namespace

int run(int argc, char** argv) {
  guardStandardDescriptors();
  guardTerminalStreams();
  const int status = runCommand(argc, argv);
  // What was printed on standard output must have arrived: else the command failed.
  if (const Status out = finishStandardOutput(); !out) {
    const bool named = argc > 1 && argv[1][0] != '-';
    const std::string who = named ? std::string("artcam ") + argv[1] : std::string("artcam");
    std::fprintf(stderr, "%s: %s\n", who.c_str(), out.message.c_str());
    return status == 0 ? 1 : status;
  }
  return status;
}

}  // namespace artcam::cli
