// SPDX-License-Identifier: Apache-2.0
// The reconstruction filters every sampler offers (sampling.h, span_sampler.h), by name as the
// CLI, the studio and the project file spell them.
#pragma once

#include <optional>
#include <string_view>

namespace artcam {

enum class Filter { Nearest, Bilinear, Bicubic };
std::string_view filterName(Filter filter);
// "nearest", "bilinear" (or "linear"), "bicubic" (or "cubic"); nullopt for anything else.
std::optional<Filter> filterFromName(std::string_view name);

}  // namespace artcam
