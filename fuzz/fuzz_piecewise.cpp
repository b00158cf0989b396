// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the .artcam reader on piecewise files (core/io/artcam_file.h), from the
// piecewise corpus.
#include "core/io/artcam_file.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const Result<Artcam> parsed = parseArtcam(fuzz::textOf(data, size), fuzz::kInputName);
  if (!parsed) fuzz::checkRefusal(parsed.status.message);
  return 0;
}
