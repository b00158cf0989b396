// SPDX-License-Identifier: Apache-2.0
// The walls CSV `artcam unfold` reads (Fig 2): the header `wall,x,y`, one corner per row in photo
// pixels, each wall's corners in order around it, the walls in the order they first appear. One
// reader with the lines CSV (matches_csv.h's labelled points: the same strict numbers, the same
// messages); bounded at kMaxWalls walls of kMaxWallCorners corners.
#pragma once

#include "core/model/status.h"
#include "core/piecewise/unfold_walls.h"

#include <string>
#include <string_view>
#include <vector>

namespace artcam {

constexpr size_t kMaxWalls = 64;
constexpr size_t kMaxWallCorners = 64;

// `name` stands for the file in messages.
Result<std::vector<WallOutline>> parseWallsCsv(std::string_view text, const std::string& name);
// A file, or "-" for standard input (text_input.h's bounds).
Result<std::vector<WallOutline>> readWallsCsv(const std::string& path);

}  // namespace artcam
