// SPDX-License-Identifier: Apache-2.0
#include "core/io/walls_csv.h"

#include "core/io/matches_csv.h"
#include "core/io/text_input.h"

namespace artcam {

Result<std::vector<WallOutline>> parseWallsCsv(std::string_view text, const std::string& name) {
  using R = Result<std::vector<WallOutline>>;
  auto labelled = parseLabelledPointsCsv(text, name, "wall");
  if (!labelled) return R::failure(labelled.status.message);
  if (labelled->size() > kMaxWalls)
    return R::failure(name + ":" + std::to_string((*labelled)[kMaxWalls].first_line) +
                      ": more than " + std::to_string(kMaxWalls) + " walls");
  std::vector<WallOutline> walls;
  for (LabelledPoints& l : *labelled) {
    if (l.points.size() > kMaxWallCorners)
      return R::failure(name + ": wall \"" + l.label + "\" (from line " +
                        std::to_string(l.first_line) + ") has more than " +
                        std::to_string(kMaxWallCorners) + " corners");
    walls.push_back({std::move(l.label), std::move(l.points)});
  }
  return R::success(std::move(walls));
}

Result<std::vector<WallOutline>> readWallsCsv(const std::string& path) {
  const Result<std::string> text = readTextInput(path);
  if (!text) return Result<std::vector<WallOutline>>::failure(text.status.message);
  return parseWallsCsv(*text, textInputName(path));
}

}  // namespace artcam
