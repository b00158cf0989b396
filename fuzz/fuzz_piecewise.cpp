// libFuzzer target: the piecewise .artcam reader (core/io/piecewise_file.h).
#include "core/io/piecewise_file.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const Result<PiecewiseDocument> parsed =
      parsePiecewiseJson(fuzz::textOf(data, size), fuzz::kInputName);
  if (!parsed) fuzz::checkRefusal(parsed.status.message);
  return 0;
}
