// SPDX-License-Identifier: Apache-2.0
// The one reader of every input read whole as text (cameras .artcam, CSVs of matches, samples,
// points and lines, studio projects, PLY clouds): the file must be a regular file, or "-" for
// standard input, and no larger than a stated cap, checked before a byte is held.
//
// Decisions:
// - The file is opened without blocking (O_NONBLOCK) and its type taken from the open file
//   (fstat), so a named pipe nobody writes, /dev/zero, a terminal or a directory is refused at
//   once with one line naming the file and what it is, never waited on or read to the end of
//   memory. The check and the read are of one open file: no window for a swap between them.
// - The cap (kMaxTextInputBytes, 64 MiB unless a reader states its own) is far above any
//   camera, CSV or project a person or the studio makes (a 24 MP photo's fully painted mask
//   of noise is a few MB of runs) and bounds what a parse may build from it: nlohmann's tree
//   of a JSON text takes a few times its size.
// - "-" reads standard input to its end, up to the same cap (a pipe is what "-" is for; a
//   terminal is refused, as the photo's "-" refuses it). Messages name it "<stdin>".
// Image files have their own readers (image_io.h), which make the same regular-file check
// (image_checks::regularFile).
#pragma once

#include "core/model/status.h"

#include <cstddef>
#include <string>

namespace artcam {

inline constexpr std::size_t kMaxTextInputBytes = std::size_t{64} << 20;

struct TextInputOptions {
  std::size_t max_bytes = kMaxTextInputBytes;
};

// The whole text of `path` ("-": standard input). Fails with one line "PATH: cannot read: …":
// no such file, not readable (the system's words), a named pipe/device/directory/socket, larger
// than the cap (naming it), or a read error.
Result<std::string> readTextInput(const std::string& path, const TextInputOptions& options = {});

// The name messages give `path`: "<stdin>" for "-", else the path.
std::string textInputName(const std::string& path);

}  // namespace artcam
