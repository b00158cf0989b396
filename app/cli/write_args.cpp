// SPDX-License-Identifier: Apache-2.0
#include "app/cli/write_args.h"

#include "core/effects/finish.h"

#include "core/io/colour_spaces.h"

namespace artcam::cli {

std::string pixelTypeForBitDepth(const std::string& bit_depth) {
  if (bit_depth == "8") return "uint8";
  if (bit_depth == "16") return "uint16";
  if (bit_depth == "half" || bit_depth == "float") return bit_depth;
  throw UsageError("--bit-depth expects 8, 16, half or float, not \"" + bit_depth + "\"");
}

void parseWriteOptions(const Args& args, WriteImageOptions& options) {
  if (args.has("--quality")) options.jpeg_quality = intOption(args, "--quality", 0, 1, 100);
  if (const auto bits = args.value("--bit-depth")) options.pixel_type = pixelTypeForBitDepth(*bits);
  if (const auto sub = args.value("--subsampling")) {
    if (*sub != "444" && *sub != "422" && *sub != "420")
      throw UsageError("--subsampling expects 444, 422 or 420, not \"" + *sub + "\"");
    options.jpeg_subsampling = std::string() + (*sub)[0] + ':' + (*sub)[1] + ':' + (*sub)[2];
  }
  if (const auto space = args.value("--colourspace")) {
    if (*space == "input")
      options.colour_space = WriteImageOptions::ColourSpace::Input;
    else if (*space == "srgb")
      options.colour_space = WriteImageOptions::ColourSpace::Srgb;
    else
      throw UsageError("--colourspace expects input or srgb, not \"" + *space + "\"");
  }
  if (const auto named = args.value("--colourspace-out")) {
    if (args.has("--colourspace"))
      throw UsageError("--colourspace and --colourspace-out both say how the output is encoded");
    if (const Status known = checkColourSpace(*named, "--colourspace-out"); !known)
      throw UsageError(known.message);
    options.ocio_colour_space = *named;
  }
}

std::string parseColourSpaceIn(const Args& args) {
  const auto named = args.value("--colourspace-in");
  if (!named) return {};
  if (const Status known = checkColourSpace(*named, "--colourspace-in"); !known)
    throw UsageError(known.message);
  return *named;
}

EdgeMode parseEdgeOption(const Args& args) {
  const auto name = args.value("--edge");
  if (!name) return EdgeMode::Transparent;
  const auto mode = edgeModeFromName(*name);
  if (!mode) throw UsageError("--edge expects transparent, extend or black, not \"" + *name + "\"");
  return *mode;
}

std::optional<std::string> parseFinishOption(const Args& args, bool allow_none) {
  const auto finish = args.value("--finish");
  if (!finish) return std::nullopt;
  if (allow_none && *finish == "none") return std::string();
  if (!finishByName(*finish)) {
    std::vector<std::string> names;
    for (const FinishInfo& f : finishes()) names.push_back(f.name);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    if (allow_none) list += ", or none";
    throw UsageError("unknown --finish \"" + *finish + "\" (" + list + ")",
                     didYouMean(*finish, names));
  }
  return *finish;
}

}  // namespace artcam::cli
