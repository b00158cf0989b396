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

// What a filter tap reads beyond the source's edge, for positions within the filter's reach
// (positions beyond it have no preimage and stay transparent, position_map.h's rule):
//   Transparent  0 in every channel (OpenImageIO's "black" wrap): the last half pixel fades
//   Extend       the nearest edge pixel (OpenImageIO's "clamp"; Hugin's nona and fulla
//                renormalise the inside taps, the same for bilinear and nearest)
//   Black        opaque black: the output composited over black, alpha full everywhere
enum class EdgeMode { Transparent, Extend, Black };
std::string_view edgeModeName(EdgeMode mode);
// "transparent", "extend", "black"; nullopt for anything else.
std::optional<EdgeMode> edgeModeFromName(std::string_view name);

}  // namespace artcam
