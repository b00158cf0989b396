// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the PLY reader (core/io/ply.h), ASCII and binary.
#include "core/io/ply.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const Result<PointCloud> parsed = parsePly(fuzz::textOf(data, size), fuzz::kInputName);
  if (!parsed) {
    fuzz::checkRefusal(parsed.status.message);
    return 0;
  }
  fuzz::require(parsed->colours.empty() || parsed->colours.size() == parsed->positions.size(),
                "one colour per point, or none");
  // The header's count was checked against the bytes: no more points than bytes.
  fuzz::require(parsed->positions.size() <= size, "no more points than bytes in the file");
  return 0;
}
