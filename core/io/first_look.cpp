// SPDX-License-Identifier: Apache-2.0
// Without the OpenImageIO module: a first look is only ever of a JPEG, which the codec path
// reads on its own (jpeg_file.h), so opening a photo in the studio shows it before the module
// that the whole read needs has loaded.
#include "core/io/first_look.h"

#include "core/colour/icc_profile.h"
#include "core/io/image_checks.h"
#include "core/io/jpeg_decode.h"
#include "core/io/jpeg_file.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace artcam {

namespace {

// Whether the whole read decodes this file's samples through the plain sRGB table: no profile
// to convert through (a damaged or CMYK one is the whole read's to report or handle).
bool decodesAsSrgb(const std::vector<unsigned char>& icc, int colour_channels, const std::string& path) {
  if (icc.empty()) return true;
  auto profile = IccProfile::fromBytes(icc, colour_channels, path);
  return profile && profile->equivalentToSrgb();
}

}  // namespace

Result<std::optional<FirstLook>> readFirstLook(const std::string& path, int box_width,
                                               int box_height,
                                               const std::function<bool(double)>& progress) {
  using R = Result<std::optional<FirstLook>>;
  if (const Status file = image_checks::regularFile(path); !file) return R::failure(file.message);
  if (!jpeg_file::startsLikeJpeg(path)) return R::success(std::nullopt);
  // The whole photo's header: what the whole read would take, and its refusals.
  auto whole = JpegDecoder::open(path);
  if (!whole) return R::failure(whole.status.message);
  const JpegDecoder& header = **whole;
  if (!header.supported()) return R::success(std::nullopt);
  const int width = header.width(), height = header.height(), channels = header.channels();
  if (const Status size = image_checks::claimedSize(path, width, height, channels, 1, true); !size)
    return R::failure(size.message);
  if (!decodesAsSrgb(header.iccProfile(), channels, path)) return R::success(std::nullopt);
  const int n = firstLookReduction(width, height, box_width, box_height);
  if (n == 1) return R::success(std::nullopt);
  whole.value.reset();

  // RGB files decoded as opaque RGBA.
  const bool rgba = channels == 3;
  auto codec = JpegDecoder::open(path, n, rgba ? JpegDecoder::Output::Rgba
                                              : JpegDecoder::Output::Samples);
  if (!codec) return R::failure(codec.status.message);
  std::unique_ptr<JpegDecoder> jpeg = std::move(*codec.value);
  const int out_channels = rgba ? 4 : 1;
  if (!jpeg->supported() || jpeg->channels() != out_channels ||
      jpeg->width() != (width + n - 1) / n || jpeg->height() != (height + n - 1) / n)
    return R::success(std::nullopt);

  FirstLook look;
  look.reduced_by = n;
  StoredImage& image = look.image;
  image = makeStoredImage(jpeg->width(), jpeg->height(), out_channels, rgba ? 3 : -1,
                          PixelType::UInt8,
                          PixelBuffer::Init::Uninitialised);  // the decoder writes every byte
  const Status decoded = jpeg->decode(
      image.bytes.data(), static_cast<size_t>(image.width) * static_cast<size_t>(out_channels),
      progress);
  jpeg.reset();  // closes the file before the metadata reader opens it
  if (!decoded) return R::failure(decoded.message);

  // Upright as the whole read turns it (same metadata, same orientation).
  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int tagged = metadata ? photoOrientation(*metadata) : 0;
  const int orientation = validOrientation(tagged != 0 ? tagged : 1);
  const bool swap = orientationSwapsAxes(orientation);
  if (orientation != 1) {
    StoredImage upright =
        makeStoredImage(swap ? image.height : image.width, swap ? image.width : image.height,
                        out_channels, image.alpha_channel, PixelType::UInt8,
                        PixelBuffer::Init::Uninitialised);
    reorientPixels(image.bytes.data(), image.width, image.height,
                   static_cast<size_t>(out_channels), orientation, upright.bytes.data());
    image = std::move(upright);
  }
  look.full_width = swap ? height : width;
  look.full_height = swap ? width : height;
  image.info = jpeg_file::describe(path, orientation, std::move(metadata));
  if (progress) progress(1.0);
  return R::success(std::move(look));
}

}  // namespace artcam
