// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the walls CSV reader of artcam unfold (core/io/walls_csv.h).
#include "core/io/walls_csv.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const auto parsed = parseWallsCsv(fuzz::textOf(data, size), fuzz::kInputName);
  if (!parsed) {
    fuzz::checkRefusal(parsed.status.message);
    return 0;
  }
  fuzz::require(!parsed->empty() && parsed->size() <= kMaxWalls, "1 to kMaxWalls walls");
  for (const WallOutline& w : *parsed) {
    fuzz::require(!w.name.empty(), "every wall is named");
    fuzz::require(!w.photo_px.empty() && w.photo_px.size() <= kMaxWallCorners,
                  "1 to kMaxWallCorners corners");
    for (const auto& p : w.photo_px) fuzz::require(p.allFinite(), "corners are finite");
  }
  return 0;
}
