// SPDX-License-Identifier: Apache-2.0
// Opening an image file for reading (io room only: it exposes OpenImageIO): the checks every
// reader makes before decoding, so readImage (float) and readStoredImage (the file's own pixel
// type) refuse the same files with the same one-line messages.
#pragma once

#include "core/colour/chromaticities.h"
#include "core/colour/transfer.h"
#include "core/io/image_io.h"
#include "core/io/io_text.h"
#include "core/io/jpeg_decode.h"
#include "core/model/status.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace artcam::io_input {

// A regular file OpenImageIO opens, with at least one pixel and channel and not a volume; alpha
// is asked for unassociated (the readers premultiply themselves). Refuses, from the header,
// sizes no codec could decode from the file's bytes and photos whose float copy would exceed
// the memory budget.
// `whole`: false for a reader that holds only bands of rows (StoredImageReader), which skips
// the memory-budget check (its caller checks what it holds).
Result<OIIO::ImageInput::unique_ptr> openImageInput(const std::string& path, bool whole = true);

// The memory one photo may take as float: ARTCAM_MAX_MEMORY_MB when set (> 0), else half of
// the machine's physical memory.
double memoryBudgetBytes();

// A decode that returned true may still have met damage: libjpeg fills a truncated JPEG with
// grey and only warns, which OIIO records as an error. Call after reading; failure names the
// file and OIIO's message.
// A damaged file makes one error per strip or scanline: the first is named, the rest counted.
inline Status decodeProblems(OIIO::ImageInput& in, const std::string& path) {
  if (!in.has_error()) return Status::success();
  std::string errors = in.geterror();
  while (!errors.empty() && errors.back() == '\n') errors.pop_back();
  const size_t first_end = errors.find('\n');
  std::string message = io_text::oneLine(errors.substr(0, first_end));
  if (first_end != std::string::npos) {
    size_t more = 0;
    for (size_t at = first_end; at != std::string::npos; at = errors.find('\n', at + 1)) ++more;
    message += " (and " + std::to_string(more) + " more decoder error" + (more == 1 ? "" : "s") +
               ": the file is damaged or cut short)";
  }
  return Status::failure(path + ": cannot read: " + message);
}

// The codec path both readers take for the pixels of `in` (opened by openImageInput): a
// libjpeg-turbo decoder for an 8-bit grey or YCbCr/RGB JPEG whose raster is what `spec` says
// (jpeg_decode.h), else null and OpenImageIO decodes. Fails (one line) when libjpeg refuses
// the header OpenImageIO accepted.
Result<std::unique_ptr<JpegDecoder>> jpegCodecPath(const OIIO::ImageInput& in,
                                                   const OIIO::ImageSpec& spec,
                                                   const std::string& path);

// Channels a reader keeps as the image (image_io.h, "Channels") and the alpha channel among
// them, or -1: colour and alpha only. With alpha among the first four, the image ends at it
// (Y A, R G B A); without, it is the colour channels, R G B (or Y when there are fewer than
// three). The rest (an EXR's Z, N.x, AOVs; a TIFF's extra samples) are extra channels,
// readExtraChannels reads them on request. One rule with and without alpha: a renderer's
// R G B Z is R G B and a Z, never a four-colour image whose Z a writer would take for alpha.
inline int keptAlpha(const OIIO::ImageSpec& spec) {
  return spec.alpha_channel >= 0 && spec.alpha_channel < 4 && spec.alpha_channel < spec.nchannels
             ? spec.alpha_channel
             : -1;
}
inline int keptChannels(const OIIO::ImageSpec& spec) {
  const int alpha = keptAlpha(spec);
  return alpha >= 0 ? alpha + 1 : spec.nchannels >= 3 ? 3 : 1;
}

// The type of the channels a reader keeps (keptChannels): the widest of their own types where
// a file's channels differ (an EXR's half RGBA beside a float Z, whose spec.format is float),
// so the image keeps its own type and the extra channels theirs.
inline OIIO::TypeDesc keptFormat(const OIIO::ImageSpec& spec) {
  if (spec.channelformats.empty()) return spec.format;
  OIIO::TypeDesc widest = spec.channelformats[0];
  const int kept = std::min(keptChannels(spec), static_cast<int>(spec.channelformats.size()));
  for (int c = 1; c < kept; ++c)
    if (spec.channelformats[static_cast<size_t>(c)].size() > widest.size())
      widest = spec.channelformats[static_cast<size_t>(c)];
  return widest;
}

// The bytes of `spec`'s embedded ICC profile ("ICCProfile"), for checkEmbeddedProfile; empty
// when it has none.
inline std::vector<unsigned char> embeddedProfileBytes(const OIIO::ImageSpec& spec) {
  const OIIO::ParamValue* attribute = spec.find_attribute("ICCProfile");
  if (!attribute) return {};
  const auto* first = static_cast<const unsigned char*>(attribute->data());
  return std::vector<unsigned char>(first, first + attribute->type().size());
}

// An OpenEXR file whose data window is not its display window is refused (image_io.h, "Data
// and display windows"): the readers hand over the data window's pixels while camera pixels
// are display-window pixels. Other formats have no separate display window.
// `data_window` (ReadImageOptions::data_window): the caller places the data window's pixels
// itself, so any data window is taken.
inline Status dataWindowIsDisplayWindow(const OIIO::ImageInput& in, const OIIO::ImageSpec& spec,
                                        const std::string& path, bool data_window = false) {
  if (data_window || std::string(in.format_name()) != "openexr") return Status::success();
  if (spec.full_width <= 0 || spec.full_height <= 0) return Status::success();
  if (spec.x == spec.full_x && spec.y == spec.full_y && spec.width == spec.full_width &&
      spec.height == spec.full_height)
    return Status::success();
  const auto window = [](int x, int y, int w, int h) {
    return std::to_string(w) + "x" + std::to_string(h) + " at (" + std::to_string(x) + ", " +
           std::to_string(y) + ")";
  };
  return Status::failure(
      path + ": cannot read: the data window (" + window(spec.x, spec.y, spec.width, spec.height) +
      ") is not the display window (" +
      window(spec.full_x, spec.full_y, spec.full_width, spec.full_height) +
      "), whose pixels the camera's are; artcam warp and batch keep it, or make " +
      "them one with oiiotool --croptofull");
}

// The primaries and white of `spec`'s RGB as its "chromaticities" attribute (OpenEXR) gives
// them, when they are not the working space's (chromaticities.h); empty for Rec.709/D65, no
// attribute, or fewer than three colour channels. Fails in one line naming `path` for
// chromaticities that make no RGB space (a y of 0, primaries on one line): guessing would
// mislabel every colour.
Result<std::optional<Chromaticities>> foreignChromaticities(const OIIO::ImageSpec& spec,
                                                            const std::string& path);

// The orientation a reader turns the raster upright from (orientation.h), 1..8: exiv2's
// photoOrientation (EXIF first, then XMP, as the photo conventions and most viewers order
// them; OpenImageIO 2.4 lets an XMP value override EXIF, and misses some XMP-only ones), else
// what OpenImageIO reports (other formats' own fields), else 1.
int storedOrientation(const OIIO::ImageSpec& spec, const PhotoMetadata* metadata);

// What both readers record about a file they decoded: format, pixel type, transfer, the spec
// turned upright (the upright size, Orientation 1), the orientation it was turned from, a
// JPEG's estimated quality and `metadata` (readPhotoMetadata's).
ImageInfo describeImage(const OIIO::ImageInput& in, const OIIO::ImageSpec& spec,
                        const std::string& path, const std::string& pixel_type,
                        const Transfer& transfer, int orientation,
                        std::shared_ptr<const PhotoMetadata> metadata);

// The spec a writer carries `like`'s metadata from: like->spec, or, for an image read without
// OpenImageIO (a JPEG through jpeg_file.h leaves it null), the file's header read again from
// like->path and turned upright as describeImage turns it. Null when there is no `like` or
// its file cannot be read any more (the metadata held in memory is still written).
std::shared_ptr<const OIIO::ImageSpec> likeSpec(const ImageInfo* like);

}  // namespace artcam::io_input
