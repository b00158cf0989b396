// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the colour-sample CSV reader (core/io/matches_csv.h), linear and sRGB-encoded
// (sRGB when the input's size is odd, as the replay test decides).
#include "core/io/matches_csv.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const ColourEncoding encoding = size % 2 ? ColourEncoding::Srgb : ColourEncoding::Linear;
  const auto parsed = parseColourSamplesCsv(fuzz::textOf(data, size), fuzz::kInputName, encoding);
  if (!parsed) {
    fuzz::checkRefusal(parsed.status.message);
    return 0;
  }
  for (const PointMatch& m : *parsed)
    fuzz::require(m.source.size() == 3 && m.target.size() == 3 && m.source.allFinite() &&
                      m.target.allFinite(),
                  "colour samples are finite RGB triples (also after sRGB decoding)");
  return 0;
}
