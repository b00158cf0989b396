// SPDX-License-Identifier: Apache-2.0
// Images through OpenImageIO 2.4, converted to the engine's linear, premultiplied ImageF.
//
// Decisions (see also image_io.h):
// - Files are opened with "oiio:UnassociatedAlpha" = 1 so OIIO hands over the stored values;
//   otherwise it premultiplies PNG/TIFF alpha itself in the ENCODED (sRGB) integer domain,
//   which is both lossy and wrong in linear light. The spec then tells us whether the stored
//   colour is associated (EXR, TIFF "associated alpha") or not (PNG, most TIFF).
// - 8/16-bit values decode through a 256/65536-entry table of the exact transfer function.
// - On write, colour is unpremultiplied (alpha 0 -> colour 0) and encoded for every format
//   except OpenEXR, whose convention is premultiplied linear; "oiio:UnassociatedAlpha" = 1
//   tells OIIO not to unpremultiply a second time.
#include "core/io/image_io.h"
#include "core/io/oiio_io.h"

#include "core/colour/icc_profile.h"
#include "core/colour/transfer.h"
#include "core/io/atomic_file.h"
#include "core/io/colour_config.h"
#include "core/io/embedded_profile.h"
#include "core/io/image_input.h"
#include "core/io/integer_decode.h"
#include "core/io/io_text.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

namespace artcam {

namespace {

using io_text::decoderFailure;
using io_text::oneLine;

std::string pixelTypeName(OIIO::TypeDesc type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8:
      return "uint8";
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16:
      return "uint16";
    case OIIO::TypeDesc::HALF:
      return "half";
    default:
      return "float";
  }
}

struct ProgressContext {
  const std::function<bool(double)>* progress = nullptr;
  bool cancelled = false;
};

// OIIO's callback returns true to ABORT; ours returns false to cancel.
bool oiioProgress(void* opaque, float portion_done) {
  auto* context = static_cast<ProgressContext*>(opaque);
  if (!(*context->progress)(static_cast<double>(portion_done))) context->cancelled = true;
  return context->cancelled;
}

template <class T>
void decodeIntegers(const std::vector<T>& stored, const Transfer& transfer, ImageF& image) {
  integer_decode::decode(stored.data(), stored.size(), transfer, image);
}

// Float path, and every case the tables do not cover.
void decodeFloats(const Transfer& transfer, bool associated_encoded, ImageF& image) {
  if (transfer.kind == Transfer::Kind::Linear) return;
  const size_t channels = static_cast<size_t>(image.channels);
  for (size_t p = 0; p < image.data.size(); p += channels) {
    float* px = image.data.data() + p;
    // Associated alpha over encoded values: unpremultiply in the encoded domain first.
    const float a = image.alpha_channel >= 0 ? px[image.alpha_channel] : 1.0f;
    const bool divide = associated_encoded && a > 0.0f;
    for (size_t c = 0; c < channels; ++c) {
      if (static_cast<int>(c) == image.alpha_channel) continue;
      const double stored = divide ? static_cast<double>(px[c]) / a : px[c];
      px[c] = static_cast<float>(transfer.decode(stored) * (divide ? a : 1.0f));
    }
  }
}

// Associated alpha over encoded values: straight colour before a profile converts it.
void unpremultiply(ImageF& image) {
  const size_t channels = static_cast<size_t>(image.channels);
  for (size_t p = 0; p < image.data.size(); p += channels) {
    float* px = image.data.data() + p;
    const float a = px[image.alpha_channel];
    if (!(a > 0.0f)) continue;
    for (size_t c = 0; c < channels; ++c)
      if (static_cast<int>(c) != image.alpha_channel) px[c] /= a;
  }
}

void premultiply(ImageF& image) {
  if (image.alpha_channel < 0) return;
  const size_t channels = static_cast<size_t>(image.channels);
  for (size_t p = 0; p < image.data.size(); p += channels) {
    float* px = image.data.data() + p;
    for (size_t c = 0; c < channels; ++c)
      if (static_cast<int>(c) != image.alpha_channel) px[c] *= px[image.alpha_channel];
  }
}

}  // namespace

namespace oiio_io {

Result<LoadedImage> readImage(const std::string& path, const ReadImageOptions& options) {
  using R = Result<LoadedImage>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  const OIIO::ImageInput::unique_ptr& in = *opened;
  const OIIO::ImageSpec spec = in->spec();
  if (const Status windows =
          io_input::dataWindowIsDisplayWindow(*in, spec, path, options.data_window);
      !windows)
    return R::failure(windows.message);

  const int channels = io_input::keptChannels(spec);
  const int alpha = io_input::keptAlpha(spec);
  const std::string pixel_type = pixelTypeName(io_input::keptFormat(spec));
  const Transfer transfer =
      Transfer::fromColourSpace(spec.get_string_attribute("oiio:ColorSpace"))
          .value_or(io_text::isIntegerPixelType(pixel_type) ? Transfer::srgb()
                                                            : Transfer::linear());
  const bool associated = alpha >= 0 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
  const bool linear = transfer.kind == Transfer::Kind::Linear;

  const bool jpeg = std::string(in->format_name()) == "jpeg";
  auto profile = checkEmbeddedProfile(io_input::embeddedProfileBytes(spec),
                                      channels - (alpha >= 0 ? 1 : 0), jpeg, path);
  if (!profile) return R::failure(profile.status.message);
  // A named colour space (colour_spaces.h) is the whole description: no profile, no primaries.
  const std::string& named = options.colour_space;
  if (!named.empty()) *profile = EmbeddedProfile{};
  const std::shared_ptr<const IccProfile>& icc = profile->converting;
  // The file's primaries and white, when not the working space's (an ACEScg EXR): its linear
  // values are converted into the working space below (chromaticities.h). A profile wins.
  auto primaries = io_input::foreignChromaticities(spec, path);
  if (!primaries) return R::failure(primaries.status.message);
  if (!named.empty()) primaries.value = std::optional<Chromaticities>();

  LoadedImage loaded;
  loaded.image = ImageF(spec.width, spec.height, channels, alpha);
  ImageF& image = loaded.image;
  ProgressContext context{options.progress ? &options.progress : nullptr};
  const OIIO::ProgressCallback callback = options.progress ? &oiioProgress : nullptr;
  auto read = [&](OIIO::TypeDesc type, void* data) {
    return in->read_image(0, 0, 0, channels, type, data, OIIO::AutoStride, OIIO::AutoStride,
                          OIIO::AutoStride, callback, &context);
  };

  bool ok = true;
  const bool tables =
      (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16) &&
      (!associated || linear);
  std::unique_ptr<JpegDecoder> codec;
  if (!icc && named.empty()) {
    auto found = io_input::jpegCodecPath(*in, spec, path);
    if (!found) return R::failure(found.status.message);
    codec = std::move(*found.value);
  }
  try {
    if (icc || !named.empty()) {
      // The profile or the named colour space converts encoded values (OIIO scales integers to
      // 0..1) to the working space.
      ok = read(OIIO::TypeDesc::FLOAT, image.data.data());
      if (ok && !context.cancelled) {
        if (associated) unpremultiply(image);
        const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
        if (icc) {
          icc->toWorking(image.data.data(), pixels, image.channels, image.alpha_channel);
        } else if (const Status converted = io_colour::toWorking(
                       named, image.data.data(), pixels, image.channels, path + ": cannot read");
                   !converted) {
          return R::failure(converted.message);
        }
      }
    } else if (codec && tables) {
      // The codec path (jpeg_decode.h), then the same tables as below.
      std::vector<std::uint8_t> stored(image.data.size());
      const Status decoded = codec->decode(
          stored.data(), static_cast<size_t>(image.width) * static_cast<size_t>(channels),
          options.progress);
      codec.reset();  // closes the file before the metadata reader opens it
      if (!decoded) return R::failure(decoded.message);
      decodeIntegers(stored, transfer, image);
    } else if (tables && spec.format == OIIO::TypeDesc::UINT8) {
      std::vector<std::uint8_t> stored(image.data.size());
      ok = read(OIIO::TypeDesc::UINT8, stored.data());
      if (ok && !context.cancelled) decodeIntegers(stored, transfer, image);
    } else if (tables) {
      std::vector<std::uint16_t> stored(image.data.size());
      ok = read(OIIO::TypeDesc::UINT16, stored.data());
      if (ok && !context.cancelled) decodeIntegers(stored, transfer, image);
    } else {
      ok = read(OIIO::TypeDesc::FLOAT, image.data.data());
      if (ok && !context.cancelled) decodeFloats(transfer, associated && !linear, image);
    }
  } catch (const std::exception& e) {  // a decoder's exception (see image_input.cpp)
    return R::failure(path + ": cannot read: " + decoderFailure(e));
  }
  if (context.cancelled) return R::failure(path + ": cannot read: cancelled");
  if (!ok) return R::failure(path + ": cannot read: " + oneLine(in->geterror()));
  if (const Status damage = io_input::decodeProblems(*in, path); !damage)
    return R::failure(damage.message);
  if (!associated || icc || !named.empty()) premultiply(image);
  if (*primaries && !icc)
    applyMatrix(workingFromChromaticities(**primaries), image.data.data(),
                static_cast<size_t>(image.width) * static_cast<size_t>(image.height),
                image.channels, image.alpha_channel);
  in->close();

  // Upright, as the photo is shown (orientation.h): a second buffer for a moment, once per read.
  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int orientation = io_input::storedOrientation(spec, metadata.get());
  if (orientation != 1) {
    const bool swap = orientationSwapsAxes(orientation);
    ImageF upright(swap ? image.height : image.width, swap ? image.width : image.height,
                   image.channels, image.alpha_channel);
    reorientPixels(image.data.data(), image.width, image.height,
                   sizeof(float) * static_cast<size_t>(image.channels), orientation,
                   upright.data.data());
    image = std::move(upright);
  }
  loaded.info = io_input::describeImage(*in, spec, path, pixel_type, transfer, orientation,
                                       std::move(metadata));
  recordEmbeddedProfile(*profile, loaded.info);
  if (!named.empty()) {
    loaded.info.ocio_colour_space = named;
    loaded.info.colour_space = "OCIO: " + named;
    loaded.info.srgb = false;
    loaded.info.chromaticities.reset();
  }
  if (options.progress) options.progress(1.0);
  return R::success(std::move(loaded));
}

}  // namespace oiio_io
}  // namespace artcam
