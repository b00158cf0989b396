// SPDX-License-Identifier: Apache-2.0
// The artcam subcommands. Each takes the arguments after its name, prints its results on
// stdout, and reports a failure by throwing: UsageError (exit 2; the error, a hint and where the
// help page is, args.h) or CommandError (exit 1): one line naming the file, the place and the
// cause. Commands that write files check them first with outputs.h.
#pragma once

#include "core/model/artcam.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace artcam::cli {

struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Command {
  const char* name;
  const char* summary;
  const char* usage;  // full --help text
  int (*run)(const std::vector<std::string>& args);
};

int fitCommand(const std::vector<std::string>& args);
int mapCommand(const std::vector<std::string>& args);
int warpCommand(const std::vector<std::string>& args);
int batchCommand(const std::vector<std::string>& args);  // artcam batch: many images, one camera
int infoCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);
int benchFitCommand(const std::vector<std::string>& args);  // artcam bench fit
int benchEffectsCommand(const std::vector<std::string>& args);  // artcam bench effects
int renderCommand(const std::vector<std::string>& args);
int presetCommand(const std::vector<std::string>& args);
int composeCommand(const std::vector<std::string>& args);
int insertCommand(const std::vector<std::string>& args);
int sampleCommand(const std::vector<std::string>& args);
int stereoCommand(const std::vector<std::string>& args);
int unfoldCommand(const std::vector<std::string>& args);
int exportCommand(const std::vector<std::string>& args);  // artcam export: a studio project
int exportMapCommand(const std::vector<std::string>& args);  // artcam export-map: an ST map
int lensCommand(const std::vector<std::string>& args);  // artcam lens: the lensfun database

extern const char* const kFitUsage;
extern const char* const kMapUsage;
extern const char* const kWarpUsage;
extern const char* const kBatchUsage;
extern const char* const kInfoUsage;
extern const char* const kBenchUsage;
extern const char* const kBenchEffectsUsage;
extern const char* const kRenderUsage;
extern const char* const kPresetUsage;
// kPresetUsage followed by the image effects of core's table (effects/effect_table.h).
std::string presetHelp();

// The camera `artcam preset NAME [--PARAM VALUE …]` makes (argv from NAME on, no -o), for
// callers that hold it instead of writing it (the Python module); the same parsing, ranges and
// messages. `summary` is the words the command prints after "wrote OUT".
struct PresetCamera {
  Artcam camera;
  std::string summary;
  bool colour_layers = false;  // render with --layers rgb
};
PresetCamera presetCamera(const std::vector<std::string>& argv);
std::vector<std::string> presetCameraNames();  // view cameras, 3D effects, image effects
std::string presetListing();                   // `artcam preset list`'s text
extern const char* const kComposeUsage;
extern const char* const kInsertUsage;
extern const char* const kSampleUsage;
extern const char* const kStereoUsage;
extern const char* const kUnfoldUsage;
extern const char* const kExportUsage;
extern const char* const kExportMapUsage;
extern const char* const kLensUsage;

int run(int argc, char** argv);

}  // namespace artcam::cli
