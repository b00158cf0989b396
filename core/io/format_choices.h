// SPDX-License-Identifier: Apache-2.0
// What the OpenImageIO writers (image_write.cpp, stored_image.cpp) ask of each format beyond
// its pixels, in one place so both write the same file (module only):
// - JPEG: the quality and chroma subsampling of jpegQualityFor / jpegSubsamplingFor.
// - PNG: --quality N sets zlib's compression level as ImageMagick reads a PNG quality, its
//   tens digit: level min(9, N / 10) (90 and over: the smallest file, 10: the fastest). PNG is
//   lossless, so the pixels are the same at every level. ImageMagick's ones digit (the row
//   filter) is not taken: OpenImageIO chooses the filters.
// - DPX: a 10- or 12-bit DPX input written back to 16-bit DPX without --bit-depth keeps its
//   bits per sample (the film scan's packing), as OpenImageIO stores uint16 in such a file.
// - Software: "artcam <version>" (photo_metadata.h's writingSoftware), for the formats whose
//   own header holds it (DPX, OpenEXR, TIFF) as exiv2 does for EXIF.
#pragma once

#include "core/io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <string>

namespace artcam::io_format {

void setFormatChoices(OIIO::ImageSpec& spec, const std::string& format,
                      const WriteImageOptions& options, const ImageInfo* like,
                      const OIIO::ImageSpec* like_spec);

}  // namespace artcam::io_format
