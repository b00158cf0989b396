// SPDX-License-Identifier: Apache-2.0
#include "core/sampling/filter.h"

namespace artcam {

std::string_view filterName(Filter filter) {
  switch (filter) {
    case Filter::Nearest: return "nearest";
    case Filter::Bilinear: return "bilinear";
    case Filter::Bicubic: return "bicubic";
  }
  return "unknown";
}

std::optional<Filter> filterFromName(std::string_view name) {
  if (name == "nearest") return Filter::Nearest;
  if (name == "bilinear" || name == "linear") return Filter::Bilinear;
  if (name == "bicubic" || name == "cubic") return Filter::Bicubic;
  return std::nullopt;
}

std::string_view edgeModeName(EdgeMode mode) {
  switch (mode) {
    case EdgeMode::Transparent:
      return "transparent";
    case EdgeMode::Extend:
      return "extend";
    case EdgeMode::Black:
      return "black";
  }
  return "unknown";
}

std::optional<EdgeMode> edgeModeFromName(std::string_view name) {
  if (name == "transparent") return EdgeMode::Transparent;
  if (name == "extend") return EdgeMode::Extend;
  if (name == "black") return EdgeMode::Black;
  return std::nullopt;
}

}  // namespace artcam
