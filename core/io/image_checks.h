// SPDX-License-Identifier: Apache-2.0
// The checks every image reader makes before decoding (the OpenImageIO module's and the JPEG
// codec's: jpeg_file.h), so both refuse the same files with the same one-line messages.
#pragma once

#include "core/model/status.h"

#include <string>

namespace artcam::image_checks {

// A regular file: fails "PATH: cannot read: no such file" or "… not a file (a named pipe)",
// naming what it is (notRegularFile). Never opens it, so a named pipe cannot block.
Status regularFile(const std::string& path);

// "not a file (a named pipe)", "… (a device)", "… (a folder)", "… (a socket)" for a stat mode
// that is not a regular file's.
std::string notRegularFile(unsigned int st_mode);

// What a header claims, before any pixel is allocated: no codec packs more than 4096 decoded
// bytes into one file byte, so a bigger claim is a corrupt or truncated file; and, for a reader
// that holds the whole photo (`whole`), its float copy must fit the memory budget.
Status claimedSize(const std::string& path, int width, int height, int channels,
                   int bytes_per_sample, bool whole);

}  // namespace artcam::image_checks
