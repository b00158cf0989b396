// SPDX-License-Identifier: Apache-2.0
// The checks every image reader makes before decoding (the OpenImageIO module's and the JPEG
// codec's: jpeg_file.h), so both refuse the same files with the same one-line messages.
#pragma once

#include "core/model/status.h"

#include <string>
#include <string_view>

namespace artcam::image_checks {

// A regular file: fails "PATH: cannot read: no such file" or "… not a file (a named pipe)",
// naming what it is (notRegularFile). Never opens it, so a named pipe cannot block.
Status regularFile(const std::string& path);

// "not a file (a named pipe)", "… (a device)", "… (a folder)", "… (a socket)" for a stat mode
// that is not a regular file's.
std::string notRegularFile(unsigned int st_mode);

// What kind of movie container `head`, a file's first bytes (512 are enough), starts like:
// "MP4", "QuickTime", "AVI", "Matroska/WebM", "MPEG", "MPEG transport stream", "Flash video",
// "Windows Media", "Ogg"; "" for none. HEIF/AVIF stills share MP4's box layout and are told by
// their brand; a brand no movie uses (a Canon CR3's "crx ") is not a movie.
// Decided: every reader refuses a movie up front. OpenImageIO 2.4's movie (ffmpeg) reader aborts
// the process on ordinary MP4 and AVI files ("double free or corruption"), so it is never
// instantiated, whatever the file's name; a frame is taken out by a movie tool first.
std::string movieContainer(std::string_view head);

// "PATH: cannot read: a movie (KIND), not a still image (...)" for movieContainer's `kind`.
std::string movieRefusal(const std::string& path, const std::string& kind);

// What a header claims, before any pixel is allocated: no codec packs more than 4096 decoded
// bytes into one file byte, so a bigger claim is a corrupt or truncated file; and, for a reader
// that holds the whole photo (`whole`), its float copy must fit the memory budget.
Status claimedSize(const std::string& path, int width, int height, int channels,
                   int bytes_per_sample, bool whole);

}  // namespace artcam::image_checks
