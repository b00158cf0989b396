// SPDX-License-Identifier: Apache-2.0
// Metadata OpenImageIO's JPEG writer could not put in a file (image module only, oiio_io.h).
//
// OpenImageIO 2.4's JPEG writer hands libjpeg each metadata block of the spec as one marker
// segment (the comment from ImageDescription, the EXIF block, the XMP packet, the IPTC block),
// and keeps libjpeg's default error_exit, which calls exit() for a segment over 65533 bytes
// ("Bogus marker length": no file named, the temporary left, a batch run ended). So before a
// JPEG is opened, each block is measured with OpenImageIO's own encoders, and while one is too
// large the largest metadata attribute is left out. The photo is written; the writer warns.
#pragma once

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

namespace artcam::io_jpeg {

// Erases from `spec` what no JPEG segment holds; returns what was left out, one phrase each
// ("ImageDescription (70000 bytes)").
std::vector<std::string> fitJpegSegments(OIIO::ImageSpec& spec);

}  // namespace artcam::io_jpeg
