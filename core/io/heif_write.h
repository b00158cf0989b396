// SPDX-License-Identifier: Apache-2.0
// HEIF and AVIF files written through libheif itself (the module only: image_write.cpp,
// stored_image.cpp), so that the photo's EXIF and XMP go into the file: exiv2 0.27 cannot
// write HEIF, and OpenImageIO 2.4's HEIF writer carries neither block. libheif's own
// metadata items (heif_context_add_exif_metadata / heif_context_add_XMP_metadata) are what
// exiftool, Apple's and Google's readers look for.
//
// Decisions:
// - The codec follows the extension as OpenImageIO's writer does: .avif is AV1, the rest
//   (.heic, .heif, .hif) HEVC. 8-bit RGB or RGBA (alpha unassociated, as HEIF stores it); a
//   grey image is written as RGB.
// - Quality: options.jpeg_quality (--quality) when given, else the encoder's default.
// - An ICC profile in `spec` is written as the image's colour profile ("prof").
// - IPTC has no place in HEIF: a photo that has it gets one "left out" line.
#pragma once

#include "core/io/photo_metadata.h"
#include "core/model/status.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace artcam::io_heif {

// True for OpenImageIO's format name "heif" (HEIC, HEIF, AVIF): those are written here.
bool writesHeif(const std::string& format);

struct HeifImage {
  int width = 0, height = 0;
  int channels = 0;  // 1–4, alpha last when channels is 2 or 4 and has_alpha
  bool has_alpha = false;
  const std::uint8_t* pixels = nullptr;  // packed rows, unassociated alpha
  std::vector<unsigned char> icc;        // empty: none
};

struct HeifMetadata {
  std::vector<unsigned char> exif;  // a TIFF-structured EXIF block (II*/MM*), or empty
  std::string xmp;                  // an XMP packet, or empty
};

// Writes `image` to `file` (an atomic save's temporary); `shown_path`, the file the user
// named, in the messages and for the codec (its extension).
Status writeHeif(const std::string& file, const std::string& shown_path, const HeifImage& image,
                 std::optional<int> quality, const HeifMetadata& metadata);

// writeHeif with the photo's metadata (null: none) updated as writePhotoMetadata updates it
// (photo_metadata.h), what cannot go in added to `left_out`; the ICC profile from `icc_spec`,
// an OIIO::ImageSpec's "ICCProfile" (as const void* so this header needs no OpenImageIO).
Status writeHeifPhoto(const std::string& file, const std::string& shown_path, HeifImage image,
                      const void* icc_spec, std::optional<int> quality,
                      const PhotoMetadata* metadata, const MetadataUpdate& update,
                      std::vector<std::string>& left_out);

}  // namespace artcam::io_heif
