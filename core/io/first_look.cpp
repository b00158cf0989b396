// SPDX-License-Identifier: Apache-2.0
#include "core/io/first_look.h"
#include "core/io/oiio_io.h"

#include "core/colour/icc_profile.h"
#include "core/colour/transfer.h"
#include "core/io/image_input.h"
#include "core/io/jpeg_decode.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace artcam {

namespace {

// Whether the whole read decodes this file's samples through the plain sRGB table: no profile
// to convert through (a damaged or CMYK one is the whole read's to report or handle).
bool decodesAsSrgb(const OIIO::ImageSpec& spec, int colour_channels, const std::string& path) {
  const Transfer transfer =
      Transfer::fromColourSpace(spec.get_string_attribute("oiio:ColorSpace"))
          .value_or(Transfer::srgb());
  if (transfer.kind != Transfer::Kind::Srgb) return false;
  const OIIO::ParamValue* attribute = spec.find_attribute("ICCProfile");
  if (!attribute) return true;
  const auto* first = static_cast<const unsigned char*>(attribute->data());
  const std::vector<unsigned char> bytes(first, first + attribute->type().size());
  auto profile = IccProfile::fromBytes(bytes, colour_channels, path);
  return profile && profile->equivalentToSrgb();
}

}  // namespace

namespace oiio_io {

Result<std::optional<FirstLook>> readFirstLook(const std::string& path, int box_width,
                                               int box_height,
                                               const std::function<bool(double)>& progress) {
  using R = Result<std::optional<FirstLook>>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  const OIIO::ImageInput::unique_ptr& in = *opened;
  const OIIO::ImageSpec spec = in->spec();
  const int channels = io_input::keptChannels(spec);
  if (io_input::keptAlpha(spec) >= 0 || (channels != 1 && channels != 3) ||
      !decodesAsSrgb(spec, channels, path))
    return R::success(std::nullopt);
  const int n = firstLookReduction(spec.width, spec.height, box_width, box_height);
  if (n == 1) return R::success(std::nullopt);
  // The codec path's test (io_input::jpegCodecPath), with RGB files decoded as opaque RGBA.
  if (std::string(in->format_name()) != "jpeg" || spec.format != OIIO::TypeDesc::UINT8)
    return R::success(std::nullopt);
  const bool rgba = channels == 3;
  auto codec = JpegDecoder::open(path, n, rgba ? JpegDecoder::Output::Rgba
                                              : JpegDecoder::Output::Samples);
  if (!codec) return R::failure(codec.status.message);
  std::unique_ptr<JpegDecoder> jpeg = std::move(*codec.value);
  const int out_channels = rgba ? 4 : 1;
  if (!jpeg->supported() || jpeg->channels() != out_channels ||
      jpeg->width() != (spec.width + n - 1) / n || jpeg->height() != (spec.height + n - 1) / n)
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
  if (const Status damage = io_input::decodeProblems(*in, path); !damage)
    return R::failure(damage.message);
  in->close();

  // Upright as the whole read turns it (same metadata, same orientation).
  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int orientation = io_input::storedOrientation(spec, metadata.get());
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
  look.full_width = swap ? spec.height : spec.width;
  look.full_height = swap ? spec.width : spec.height;
  image.info = io_input::describeImage(*in, spec, path, "uint8", Transfer::srgb(), orientation,
                                       std::move(metadata));
  if (progress) progress(1.0);
  return R::success(std::move(look));
}

}  // namespace oiio_io
}  // namespace artcam
