// SPDX-License-Identifier: Apache-2.0
#include "core/io/colour_config.h"

#include "core/io/io_text.h"

#include <OpenImageIO/color.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

namespace artcam::io_colour {

namespace {

// The names the working space goes by in the configs people use: OCIO 2's ACES CG and studio
// configs (lin_rec709 is their alias of "Linear Rec.709 (sRGB)"), the ACES 1.x configs, and
// OpenImageIO's built-in one.
const char* const kWorkingNames[] = {"lin_rec709", "Linear Rec.709 (sRGB)",
                                     "Utility - Linear - sRGB", "linear"};

struct Config {
  std::unique_ptr<OIIO::ColorConfig> config;
  std::string name;                // "built-in" or the file $OCIO names
  std::string working;             // the config's name of the working space; empty: none
  std::string error;               // why the config cannot be used
  std::vector<std::string> names;  // colour spaces, aliases and roles
};

const Config& config() {
  static const Config loaded = [] {
    Config c;
    c.config = std::make_unique<OIIO::ColorConfig>();
    c.name = c.config->configname();
    // Without $OCIO, OpenImageIO 2.4 records a missing-file error and goes on with its built-in
    // config: only a config without colour spaces is unusable.
    if (c.config->getNumColorSpaces() > 0) c.config->geterror();
    // A $OCIO that OpenImageIO could not read leaves it on its built-in config: said, not used.
    const char* named = std::getenv("OCIO");
    if (named && *named && c.name == "built-in") {
      c.error = std::string("the OpenColorIO config $OCIO names (") + named + ") cannot be read";
      return c;
    }
    if (c.config->getNumColorSpaces() <= 0) {
      c.error = "the OpenColorIO config " + c.name +
                " cannot be read: " + io_text::oneLine(c.config->geterror());
      return c;
    }
    for (const std::string& space : c.config->getColorSpaceNames()) {
      c.names.push_back(space);
      for (const std::string& alias : c.config->getAliases(space)) c.names.push_back(alias);
    }
    const size_t spaces = c.names.size();
    for (const std::string& role : c.config->getRoles()) c.names.push_back(role);
    for (const char* candidate : kWorkingNames)
      if (std::find(c.names.begin(), c.names.begin() + static_cast<long>(spaces), candidate) !=
          c.names.begin() + static_cast<long>(spaces)) {
        c.working = candidate;
        break;
      }
    if (c.working.empty())
      c.error = "the OpenColorIO config " + c.name + " has no linear Rec.709 colour space (" +
                "lin_rec709, \"Linear Rec.709 (sRGB)\", \"Utility - Linear - sRGB\" or linear), " +
                "the engine's working space";
    return c;
  }();
  return loaded;
}

std::string someNames(const Config& c) {
  std::string list;
  const size_t shown = std::min<size_t>(c.config->getNumColorSpaces(), 8);
  for (size_t k = 0; k < shown; ++k)
    list += (k ? ", " : "") + std::string(c.config->getColorSpaceNameByIndex(static_cast<int>(k)));
  if (static_cast<size_t>(c.config->getNumColorSpaces()) > shown) list += ", …";
  return list;
}

Status convert(const std::string& from, const std::string& to, float* data, size_t pixels,
               int channels, const std::string& what) {
  const Config& c = config();
  if (!c.error.empty()) return Status::failure(what + ": " + c.error);
  if (channels != 3 && channels != 4)
    return Status::failure(what + ": an OpenColorIO colour space needs RGB colour, the image has " +
                           std::to_string(channels) + " channels");
  // ColorConfig makes processors under its own lock, and a processor applies from any thread.
  OIIO::ColorProcessorHandle processor = c.config->createColorProcessor(from, to);
  if (!processor)
    return Status::failure(what + ": OpenColorIO cannot convert from " + from + " to " + to + ": " +
                           io_text::oneLine(c.config->geterror()));
  if (processor->isNoOp()) return Status::success();
  // In rows of at most 2^20 pixels: apply takes int sizes.
  constexpr size_t kRow = size_t{1} << 20;
  const OIIO::stride_t pixel = static_cast<OIIO::stride_t>(sizeof(float)) * channels;
  for (size_t p = 0; p < pixels; p += kRow) {
    const int n = static_cast<int>(std::min(kRow, pixels - p));
    processor->apply(data + p * static_cast<size_t>(channels), n, 1, channels, sizeof(float), pixel,
                     pixel * n);
  }
  return Status::success();
}

}  // namespace

Status checkColourSpace(const std::string& name, const std::string& option) {
  const Config& c = config();
  if (!c.error.empty()) return Status::failure(option + ": " + c.error);
  if (std::find(c.names.begin(), c.names.end(), name) != c.names.end()) return Status::success();
  return Status::failure(option + ": no colour space \"" + name + "\" in the OpenColorIO config " +
                         c.name + " (" + someNames(c) + ")");
}

Status toWorking(const std::string& name, float* data, size_t pixels, int channels,
                 const std::string& what) {
  return convert(name, config().working, data, pixels, channels, what);
}

Status fromWorking(const std::string& name, float* data, size_t pixels, int channels,
                   const std::string& what) {
  return convert(config().working, name, data, pixels, channels, what);
}

std::optional<Chromaticities> linearChromaticities(const std::string& name) {
  const Config& c = config();
  if (!c.error.empty()) return std::nullopt;
  // The basis, then values that a matrix must map as the basis says (scaled, negative, > 1).
  const float probe[6][3] = {
      {1, 0, 0},          {0, 1, 0}, {0, 0, 1}, {0.3f, 0.6f, 0.1f}, {0.75f, 1.5f, 0.25f},
      {-0.2f, 0.4f, 1.3f}};
  float values[6][3];
  std::memcpy(values, probe, sizeof values);
  if (!fromWorking(name, &values[0][0], 6, 3, "probe")) return std::nullopt;
  Matrix3 m{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) m[static_cast<size_t>(r * 3 + k)] = values[k][r];
  for (int p = 3; p < 6; ++p)
    for (int r = 0; r < 3; ++r) {
      double want = 0;
      for (int k = 0; k < 3; ++k) want += m[static_cast<size_t>(r * 3 + k)] * probe[p][k];
      if (!(std::fabs(want - values[p][r]) <= 1e-5 * (1.0 + std::fabs(want)))) return std::nullopt;
    }
  return chromaticitiesOfMatrix(m);
}

}  // namespace artcam::io_colour
