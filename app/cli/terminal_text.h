// SPDX-License-Identifier: Apache-2.0
// What reaches a terminal from text the user did not type as a command: file names from a
// folder, CSV labels, lens and camera names from EXIF or lensfun, keys of a project. A control
// character in them (ESC, CSI, BEL, CR, ...) would move the cursor, retitle the window or
// rewrite what is already on screen; GNU ls and git show such names escaped, and so does artcam.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace artcam::cli {

// `text` with every control character but tab and newline (C0, DEL, and C1 as UTF-8) written as
// a visible escape: "\x1b", "\r", "\u009b".
std::string terminalSafe(std::string_view text);

// When standard output or standard error is a terminal, routes it (stdout, stderr) through
// terminalSafe. Run once, first thing. Pipes and files are left byte for byte as they were.
void guardTerminalStreams();

// The unfiltered standard error, for the progress line's own "\r\033[K".
std::FILE* terminalControlStream();

}  // namespace artcam::cli
