// SPDX-License-Identifier: Apache-2.0
// JPEG files in and out through libjpeg-turbo and exiv2 alone, without the OpenImageIO module
// (oiio_io.h): `artcam warp photo.jpg out.jpg`, the commonest job, then never loads the ~250
// libraries behind OpenImageIO, whose loading alone cost more than decoding the photo.
//
// The stored-type entry points (stored_image.h) come here first and fall back to the module
// for anything this path does not take (nullopt): other formats, CMYK or 12-bit JPEGs, writes
// that change the pixel type or carry extra channels, a JPEG written from a non-JPEG input
// (whose header metadata only OpenImageIO reads). What it takes, it does as the module would:
// - Reading (stored samples, or linear float for readImage): the module's refusals
//   (image_checks.h), the same samples (jpeg_decode.h is the module's JPEG codec path too),
//   turned upright the same way, the same ImageInfo but for
//   `spec`, which stays null (image_io.h: writers that need it read it again from the file).
// - Writing: OpenImageIO 2.4's JPEG writer's choices, so either path writes the same bytes:
//   jpeg_set_defaults (islow DCT, standard Huffman tables), the quality of jpegQualityFor and
//   the chroma subsampling of jpegSubsamplingFor, a JFIF header whose density is the input's, the
//   input's comment and ICC profile; then exiv2 writes the input's EXIF, IPTC and XMP, as every
//   writer does. Colour is written as it is held, premultiplied (a JPEG has no alpha: composited
//   over black).
#pragma once

#include "core/io/stored_image.h"

#include <memory>
#include <optional>
#include <string>

namespace artcam::jpeg_file {

// A file that starts with a JPEG start-of-image marker (FF D8 FF), as OpenImageIO's reader
// checks; the extension does not matter for reading.
bool startsLikeJpeg(const std::string& path);

// The ImageInfo the module's readers give an 8-bit sRGB JPEG, but `spec` (null here): format,
// pixel type, transfer, orientation turned from, estimated quality, metadata.
ImageInfo describe(const std::string& path, int stored_orientation,
                   std::shared_ptr<const PhotoMetadata> metadata);

// What readStoredShape and readStoredImage give a JPEG this path decodes; nullopt for any
// other file.
std::optional<Result<StoredShape>> readShape(const std::string& path);
std::optional<Result<StoredImage>> readStored(const std::string& path, const ReadImageOptions& options);

// What readImage gives a JPEG this path decodes whose colours need no profile (none embedded,
// or one equivalent to sRGB): the sRGB table's linear floats; nullopt for any other file (a
// JPEG with an Adobe RGB or grey-gamma profile is converted by the module's lcms2 path).
std::optional<Result<LoadedImage>> readFloat(const std::string& path, const ReadImageOptions& options);

// Whether `path`'s extension names JPEG (.jpg, .jpeg, .jpe, .jif, .jfif, .jfi, any case), the
// writer OpenImageIO would pick.
bool jpegExtension(const std::string& path);

// writeStoredImageBands into a JPEG; nullopt when the write is not one this path takes.
std::optional<Status> writeBands(const std::string& path, const ConstImageView& shape,
                                 const ImageInfo* like, const WriteImageOptions& options,
                                 const StoredBandSource& band_rows);

}  // namespace artcam::jpeg_file
