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

}  // namespace artcam
