// SPDX-License-Identifier: Apache-2.0
// The quality a JPEG was saved with, estimated from its luminance quantisation table.
// OpenImageIO 2.4 does not report it on read, and writers keep no quality field, so it is
// recovered the way ImageMagick does: the IJG quality (1..100) whose scaled standard table is
// nearest the file's. Files made by libjpeg (and so OpenImageIO, cameras' firmware using IJG
// scaling, most editors) give their quality back exactly; other encoders get the nearest.
#pragma once

#include <string>

namespace artcam {

// 1..100, or 0 when `path` is no JPEG or has no readable 8-bit luminance table. Reads only
// the header segments (stops at the first scan), bounds-checked: a hostile file gives 0.
int estimateJpegQuality(const std::string& path);

// A colour JPEG's chroma subsampling from its frame header (SOF): "4:4:4", "4:2:2", "4:2:0",
// "4:4:0" or "4:1:1" from the luma component's sampling factors over the chroma ones (as
// exiftool's YCbCrSubSampling names them); "" for a grey or an unusual layout, no JPEG, or a
// header that does not parse (the same bounds-checked walk as the quality's).
std::string jpegSubsampling(const std::string& path);

}  // namespace artcam
