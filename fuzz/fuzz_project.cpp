// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the project file's one reader (core/project/studio_project.h), which the
// studio and `artcam export` both use.
#include "core/project/studio_project.h"
#include "fuzz/fuzz_check.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The reader names the file by its file name; relative paths resolve against its folder.
  const Result<StudioProject> parsed =
      parseStudioProject(text, "/nonexistent/fuzz-input.artcamproj");
  if (!parsed) fuzz::checkRefusal(parsed.status.message, "fuzz-input.artcamproj");
  return 0;
}
