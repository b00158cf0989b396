// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the match-list CSV reader (core/io/matches_csv.h), 2D and 3D, and the
// traced-lines CSV beside it: lines when the text starts "line", else 3D when it names src_z
// (as the replay test tests/core/io/test_hostile_inputs.cpp decides), so one corpus covers the
// three headers.
#include "core/io/matches_csv.h"
#include "fuzz/fuzz_check.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const std::string_view text = fuzz::textOf(data, size);
  if (text.substr(0, 4) == "line") {
    const auto lines = parseLinesCsv(text, fuzz::kInputName);
    if (!lines) {
      fuzz::checkRefusal(lines.status.message);
      return 0;
    }
    for (const LineTrace& line : *lines)
      for (const auto& p : line.points) fuzz::require(p.allFinite(), "traced points are finite");
    return 0;
  }
  const int dimension = text.find("src_z") != std::string_view::npos ? 3 : 2;
  const auto parsed = parseMatchesCsv(text, fuzz::kInputName, dimension);
  if (!parsed) {
    fuzz::checkRefusal(parsed.status.message);
    return 0;
  }
  for (const PointMatch& m : *parsed)
    fuzz::require(m.source.size() == dimension && m.target.size() == dimension &&
                      m.source.allFinite() && m.target.allFinite(),
                  "matches have the header's dimension and finite coordinates");
  return 0;
}
