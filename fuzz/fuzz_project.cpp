// SPDX-License-Identifier: Apache-2.0
// libFuzzer target: the studio's project reader (ui/project_file.h; Qt JSON, so this target is
// built from ui/project_file.cpp alone with Qt Core, without the rest of the GUI).
#include "fuzz/fuzz_check.h"
#include "ui/project_file.h"

#include <QByteArray>
#include <QString>

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace artcam;
  const QByteArray json(reinterpret_cast<const char*>(data), static_cast<qsizetype>(size));
  // parseProject names the file by its file name; relative paths resolve against its folder.
  const Result<ui::Project> parsed =
      ui::parseProject(json, QStringLiteral("/nonexistent/fuzz-input.artcamproj"));
  if (!parsed) fuzz::checkRefusal(parsed.status.message, "fuzz-input.artcamproj");
  return 0;
}
