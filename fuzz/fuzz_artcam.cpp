// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the .artcam reader (core/io/artcam_file.h): layers, outputs, patches.
// A file that parses must also write back and parse again (the writer refuses nothing the
// reader accepted).
#include "core/io/artcam_file.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const auto text = fuzz::textOf(data, size);
  const Result<Artcam> parsed = parseArtcam(text, fuzz::kInputName);
  if (!parsed) {
    fuzz::checkRefusal(parsed.status.message);
    return 0;
  }
  const std::string written = toArtcamJson(*parsed);
  const Result<Artcam> again = parseArtcam(written, "rewritten");
  if (!again) std::fprintf(stderr, "%s\n", again.status.message.c_str());
  fuzz::require(again.ok(), "a parsed .artcam must read back after writing");
  return 0;
}
