// SPDX-License-Identifier: Apache-2.0
// writeImage (declared in image_io.h): ImageF (linear, premultiplied) -> any OIIO format,
// atomically. The decisions are listed in image_io.h.
#include "core/colour/icc_profile.h"
#include "core/colour/quantise8.h"
#include "core/colour/transfer.h"
#include "core/io/atomic_file.h"
#include "core/io/checked_output.h"
#include "core/io/colour_config.h"
#include "core/io/extra_channels.h"
#include "core/io/format_choices.h"
#include "core/io/heif_write.h"
#include "core/io/image_input.h"
#include "core/io/image_io.h"
#include "core/io/io_text.h"
#include "core/io/jpeg_segments.h"
#include "core/io/oiio_io.h"
#include "core/io/photo_metadata.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>

namespace artcam {

namespace {

using io_text::lower;
using io_text::oneLine;
using io_text::replaceAll;

bool isIntegerType(const std::string& type) { return io_text::isIntegerPixelType(type); }

OIIO::TypeDesc typeOf(const std::string& pixel_type) {
  if (pixel_type == "uint8") return OIIO::TypeDesc::UINT8;
  if (pixel_type == "uint16") return OIIO::TypeDesc::UINT16;
  if (pixel_type == "half") return OIIO::TypeDesc::HALF;
  return OIIO::TypeDesc::FLOAT;
}

// The pixel type the format can actually store, closest to the one asked for.
std::string fitPixelType(const std::string& wanted, const std::string& format) {
  static const std::set<std::string> kEightBitOnly{"jpeg", "bmp", "targa", "gif",
                                                   "webp", "ico", "heif"};
  if (format == "openexr") return isIntegerType(wanted) ? "half" : wanted;
  if (format == "hdr") return "float";
  if (kEightBitOnly.count(format)) return "uint8";
  if (format == "png" || format == "pnm") return isIntegerType(wanted) ? wanted : "uint16";
  return wanted;
}

std::string naturalPixelType(const std::string& format) {
  return format == "openexr" ? "half" : format == "hdr" ? "float" : "uint8";
}

// Whether an attribute of the source file still describes the written one.
bool keepAttribute(const std::string& name, bool same_format, bool same_transfer) {
  const std::string n = lower(name);
  if (n == "compression" || n == "compressionquality") return same_format;
  if (n == "iccprofile" || n == "exif:colorspace") return same_transfer;
  if (n.rfind("thumbnail_", 0) == 0 || n == "planarconfig") return false;
  if (n == "exif:pixelxdimension" || n == "exif:pixelydimension") return false;
  const size_t colon = n.find(':');
  if (colon == std::string::npos) return true;
  // Prefixed names are standard metadata blocks or format-private details (tiff:, png:, oiio:).
  static const std::set<std::string> kPortable{"exif", "gps", "iptc", "xmp", "photoshop"};
  return kPortable.count(n.substr(0, colon)) > 0;
}

std::vector<std::string> defaultChannelNames(int channels, int alpha) {
  std::vector<std::string> names;
  const char* colour_names[] = {"R", "G", "B"};
  const int colours = channels - (alpha >= 0 ? 1 : 0);
  int next_colour = 0;
  for (int c = 0; c < channels; ++c) {
    if (c == alpha)
      names.push_back("A");
    else if (colours == 1)
      names.push_back("Y"), ++next_colour;
    else
      names.push_back(next_colour < 3 ? colour_names[next_colour++] : "A");
  }
  return names;
}

// Straight colour from associated and back, over interleaved values (alpha 0: colour 0).
void unpremultiplyValues(float* data, size_t pixels, int channels, int alpha) {
  for (size_t p = 0; p < pixels; ++p) {
    float* px = data + p * static_cast<size_t>(channels);
    const float a = px[alpha];
    for (int c = 0; c < channels; ++c)
      if (c != alpha) px[c] = a > 0.0f ? px[c] / a : 0.0f;
  }
}
void premultiplyValues(float* data, size_t pixels, int channels, int alpha) {
  for (size_t p = 0; p < pixels; ++p) {
    float* px = data + p * static_cast<size_t>(channels);
    for (int c = 0; c < channels; ++c)
      if (c != alpha) px[c] *= px[alpha];
  }
}

template <class T>
std::vector<T> quantise(const std::vector<float>& values) {
  constexpr double kMax = static_cast<double>(std::numeric_limits<T>::max());
  std::vector<T> out(values.size());
  for (size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    // !(v > 0) also catches NaN.
    out[k] = static_cast<T>(!(v > 0.0) ? 0.0 : v >= 1.0 ? kMax : std::floor(v * kMax + 0.5));
  }
  return out;
}

}  // namespace

namespace oiio_io {

Status writeImage(const std::string& path, const ImageF& image, const ImageInfo* like,
                  const WriteImageOptions& options) {
  const std::string fail = path + ": cannot write: ";
  if (image.empty()) return Status::failure(fail + "the image is empty");
  if (image.channels < 1 || image.channels > 4 || image.alpha_channel >= image.channels ||
      image.data.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
                               static_cast<size_t>(image.channels))
    return Status::failure(fail + "malformed image (channels or data size)");

  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) {
    OIIO::geterror();  // clear the thread's pending message
    const std::string extension = std::filesystem::path(path).extension().string();
    return Status::failure(path + (extension.empty()
                                       ? ": no file extension to choose an image format from"
                                       : ": no image format for extension \"" + extension + "\""));
  }
  const std::string format = out->format_name();
  // OIIO 2.4's JPEG writer lets libjpeg's default error handler call exit() on this error, so
  // it must never reach it.
  constexpr int kJpegMaxSide = 65500;
  if (format == "jpeg" && (image.width > kJpegMaxSide || image.height > kJpegMaxSide))
    return Status::failure(fail + "JPEG stores at most " + std::to_string(kJpegMaxSide) +
                           " pixels per side, the image is " + std::to_string(image.width) + "x" +
                           std::to_string(image.height));

  std::string wanted = options.pixel_type;
  if (wanted.empty() && like) wanted = like->pixel_type;
  if (wanted.empty()) wanted = naturalPixelType(format);
  if (!isIntegerType(wanted) && wanted != "half" && wanted != "float")
    return Status::failure(fail + "unknown pixel type \"" + wanted +
                           "\" (uint8, uint16, half or float)");
  const std::string pixel_type = fitPixelType(wanted, format);
  const bool integer = isIntegerType(pixel_type);

  std::optional<Transfer> like_transfer =
      like ? Transfer::fromColourSpace(like->colour_space) : std::nullopt;
  if (like && !like_transfer) like_transfer = like->srgb ? Transfer::srgb() : Transfer::linear();
  // A named OpenColorIO colour space (colour_spaces.h) encodes the output on its own: the
  // values reach it as linear working-space light, no transfer, profile or primaries beside it.
  const std::string& named = options.ocio_colour_space;
  const bool want_srgb =
      named.empty() && options.colour_space == WriteImageOptions::ColourSpace::Srgb;
  // An integer input converted through a profile keeps no transfer of its own: where its
  // profile does not encode the output (below), sRGB does.
  const Transfer transfer = !integer || !named.empty() ? Transfer::linear()
                            : like && isIntegerType(like->pixel_type) && !like->icc &&
                                    like->ocio_colour_space.empty() && !want_srgb
                                ? *like_transfer
                                : Transfer::srgb();

  // The profile integer values are encoded in (image_io.h, "Output colour"): `like`'s converting
  // profile by default, where it describes these channels; sRGB's when asked for.
  const int colour_channels = image.channels - (image.alpha_channel >= 0 ? 1 : 0);
  const IccProfile* encode_icc = integer && named.empty() && !want_srgb && like && like->icc &&
                                         like->icc->colourChannels() == colour_channels
                                     ? like->icc.get()
                                     : nullptr;
  const bool same_encoding = !named.empty()      ? false
                             : encode_icc        ? isIntegerType(like->pixel_type)
                             : like && like->icc ? false
                                                 : like_transfer && *like_transfer == transfer;

  const bool keep_alpha = image.alpha_channel >= 0 && out->supports("alpha");
  const bool associated = format == "openexr";
  const int channels = image.channels - (image.alpha_channel >= 0 && !keep_alpha ? 1 : 0);
  const int alpha = keep_alpha ? image.alpha_channel : -1;

  OIIO::ImageSpec spec(image.width, image.height, channels, typeOf(pixel_type));
  const std::shared_ptr<const OIIO::ImageSpec> like_spec_held = io_input::likeSpec(like);
  const OIIO::ImageSpec* like_spec = like_spec_held.get();
  if (like_spec) {
    const bool same_format = like->format_name == format;
    for (const OIIO::ParamValue& p : like_spec->extra_attribs)
      if (keepAttribute(p.name().string(), same_format, same_encoding))
        spec.extra_attribs.push_back(p);
    // A profile that does not describe the values (embedded_profile.h) labels no output.
    if (!like->profile_dropped.empty()) spec.erase_attribute("ICCProfile");
  }
  // An OpenEXR output of an input in other primaries (an ACEScg plate) goes back into them by
  // default, as an integer output goes back into its input's profile: a plate keeps its space.
  const std::optional<Chromaticities> file_primaries = !integer && format == "openexr" && like &&
                                                               like->chromaticities && !like->icc &&
                                                               named.empty() && !want_srgb
                                                           ? like->chromaticities
                                                           : std::nullopt;
  const std::optional<Matrix3> to_file_primaries =
      file_primaries ? std::optional<Matrix3>(chromaticitiesFromWorking(*file_primaries))
                     : std::nullopt;
  if (!integer) {
    // Float files hold the working space (or the input's primaries, above); OpenEXR names its
    // primaries and white, others are linear by convention. No ICC profile describes them.
    spec.erase_attribute("ICCProfile");
    spec.erase_attribute("chromaticities");
    if (format == "openexr" && named.empty()) {
      const Chromaticities label = file_primaries ? *file_primaries : Chromaticities::rec709();
      float xy[8];
      for (size_t k = 0; k < 8; ++k) xy[k] = static_cast<float>(label.xy[k]);
      spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), xy);
    } else if (format == "openexr") {
      // A named space that is a matrix from the working space has primaries: they are named.
      if (const auto named_primaries = io_colour::linearChromaticities(named)) {
        float xy[8];
        for (size_t k = 0; k < 8; ++k) xy[k] = static_cast<float>(named_primaries->xy[k]);
        spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), xy);
      }
    }
  } else {
    spec.erase_attribute("chromaticities");  // integer values are encoded from the working space
  }
  if (integer && (encode_icc || want_srgb)) {
    const std::vector<unsigned char> profile =
        encode_icc ? encode_icc->bytes() : IccProfile::srgbBytes();
    spec.erase_attribute("ICCProfile");
    spec.attribute("ICCProfile",
                   OIIO::TypeDesc(OIIO::TypeDesc::UINT8, static_cast<int>(profile.size())),
                   profile.data());
  }
  // `like`'s names for the channels the image kept of it (its colour and alpha).
  if (!options.channel_names.empty() &&
      options.channel_names.size() != static_cast<size_t>(channels))
    return Status::failure(path +
                           ": cannot write: " + std::to_string(options.channel_names.size()) +
                           " channel names for " + std::to_string(channels) + " channels");
  spec.channelnames = !options.channel_names.empty() ? options.channel_names
                      : like_spec && io_input::keptChannels(*like_spec) == channels &&
                              io_input::keptAlpha(*like_spec) == alpha &&
                              static_cast<int>(like_spec->channelnames.size()) >= channels
                          ? std::vector<std::string>(like_spec->channelnames.begin(),
                                                     like_spec->channelnames.begin() + channels)
                          : defaultChannelNames(channels, alpha);
  spec.alpha_channel = alpha;
  io_extra::keepDisplayWindow(spec, format, like_spec);
  if (const Status extra = io_extra::addExtraChannels(spec, format, options.extra_channels, path);
      !extra)
    return extra;
  const bool with_extra = options.extra_channels && !options.extra_channels->empty();
  // The profile is the whole label: no transfer tag (a PNG sRGB or gAMA chunk) beside it.
  if (!named.empty())
    spec.attribute("oiio:ColorSpace", named);
  else if (encode_icc)
    spec.erase_attribute("oiio:ColorSpace");
  else
    spec.attribute("oiio:ColorSpace", transfer.colourSpaceName());
  if (alpha >= 0 && !associated) spec.attribute("oiio:UnassociatedAlpha", 1);
  std::vector<std::string> left_out;  // metadata the output cannot hold (one warning)
  io_format::setFormatChoices(spec, format, options, like, like_spec);
  if (format == "jpeg") left_out = io_jpeg::fitJpegSegments(spec);

  // Encoded values in the written channel order, a band of rows at a time: no whole-image
  // copy beside the float image (big images). Each written sample of rows [y0, y1) in order:
  // colour as linear light (divided by alpha for unassociated output) to `colour`, a kept
  // alpha as it is to `alpha_sample`.
  const size_t in_channels = static_cast<size_t>(image.channels);
  const bool divide = alpha >= 0 && !associated;  // unassociated output; alpha 0 has no colour
  auto forEachSample = [&](int y0, int y1, auto&& colour, auto&& alpha_sample) {
    const size_t begin = static_cast<size_t>(y0) * static_cast<size_t>(image.width) * in_channels;
    const size_t end = static_cast<size_t>(y1) * static_cast<size_t>(image.width) * in_channels;
    for (size_t p = begin; p < end; p += in_channels) {
      const float* px = image.data.data() + p;
      const float a = image.alpha_channel >= 0 ? px[image.alpha_channel] : 1.0f;
      for (size_t c = 0; c < in_channels; ++c) {
        if (static_cast<int>(c) == image.alpha_channel) {
          if (keep_alpha) alpha_sample(a);
          continue;
        }
        colour(!divide ? px[c] : a > 0.0f ? static_cast<double>(px[c]) / a : 0.0);
      }
    }
  };
  auto encodeRows = [&](int y0, int y1, std::vector<float>& encoded) -> Status {
    encoded.clear();
    forEachSample(
        y0, y1,
        [&](double linear) {
          encoded.push_back(encode_icc ? static_cast<float>(linear)
                                       : static_cast<float>(transfer.encode(linear)));
        },
        [&](float a) { encoded.push_back(a); });
    if (encode_icc)
      encode_icc->fromWorking(encoded.data(), encoded.size() / static_cast<size_t>(channels),
                              channels, alpha);

    if (to_file_primaries)
      applyMatrix(*to_file_primaries, encoded.data(),
                  encoded.size() / static_cast<size_t>(channels), channels, alpha);
    if (named.empty()) return Status::success();
    // OpenColorIO converts straight colour: an associated output's is divided out and back.
    const size_t pixels = encoded.size() / static_cast<size_t>(channels);
    if (alpha >= 0 && associated) unpremultiplyValues(encoded.data(), pixels, channels, alpha);
    const Status converted = io_colour::fromWorking(named, encoded.data(), pixels, channels,
                                                    fail.substr(0, fail.size() - 2));
    if (alpha >= 0 && associated) premultiplyValues(encoded.data(), pixels, channels, alpha);
    return converted;
  };
  // 8-bit output through a transfer (no profile to convert through): straight to bytes by the
  // thresholds of quantise8.h, the same integers as encoding each sample and rounding it.
  std::optional<Quantise8> to_byte, alpha_to_byte;
  if (pixel_type == "uint8" && !encode_icc && !with_extra && named.empty()) {
    to_byte.emplace(transfer);
    if (keep_alpha) alpha_to_byte.emplace(Transfer::linear());
  }
  auto byteRows = [&](int y0, int y1, std::vector<std::uint8_t>& out_bytes) {
    out_bytes.clear();
    forEachSample(
        y0, y1, [&](double linear) { out_bytes.push_back((*to_byte)(linear)); },
        [&](float a) { out_bytes.push_back((*alpha_to_byte)(a)); });
  };
  const OIIO::TypeDesc data_type = pixel_type == "uint8"    ? OIIO::TypeDesc::UINT8
                                   : pixel_type == "uint16" ? OIIO::TypeDesc::UINT16
                                                            : OIIO::TypeDesc::FLOAT;

  // A multi-part OpenEXR's later parts, after the image's (extra_channels.h).
  auto part_specs = io_extra::partSpecs(spec, format, options.other_parts, path);
  if (!part_specs) return part_specs.status;
  const Status written = writeAtomically(path, [&](const std::string& temp) {
    // OIIO names the file it was given; the user knows only the target.
    auto failure = [&](const std::string& message) {
      return Status::failure(fail + replaceAll(oneLine(message), temp, path));
    };
    if (io_heif::writesHeif(format)) {  // 8-bit (fitPixelType), through libheif with metadata
      std::vector<std::uint8_t> all, rows;
      std::vector<float> encoded_rows;
      for (int y0 = 0; y0 < image.height; y0 += 64) {
        if (options.progress && !options.progress(static_cast<double>(y0) / image.height))
          return failure("cancelled");
        const int y1 = std::min(image.height, y0 + 64);
        if (to_byte) {
          byteRows(y0, y1, rows);
        } else {
          encodeRows(y0, y1, encoded_rows);
          rows = quantise<std::uint8_t>(encoded_rows);
        }
        all.insert(all.end(), rows.begin(), rows.end());
      }
      io_heif::HeifImage heif{image.width, image.height, channels, alpha >= 0, all.data(), {}};
      return io_heif::writeHeifPhoto(temp, path, std::move(heif), &spec, options.jpeg_quality,
                                     like ? like->metadata.get() : nullptr,
                                     {image.width, image.height, same_encoding}, left_out);
    }
    io_checked::CheckedWrite checked(std::move(out));
    if (!checked.open(temp, *part_specs)) return failure(checked.cause());
    constexpr int kBand = 64;
    std::vector<float> encoded;
    std::vector<float> with_channels;
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint16_t> words;
    bool ok = true;
    for (int y0 = 0; ok && y0 < image.height; y0 += kBand) {
      if (options.progress && !options.progress(static_cast<double>(y0) / image.height))
        return failure("cancelled");
      const int y1 = std::min(image.height, y0 + kBand);
      if (to_byte) {
        byteRows(y0, y1, bytes);
        ok = checked.output().write_scanlines(spec.y + y0, spec.y + y1, 0, data_type, bytes.data());
        continue;
      }
      if (const Status band = encodeRows(y0, y1, encoded); !band) return band;
      const void* data = encoded.data();
      if (with_extra) {  // OpenEXR only, so float samples
        io_extra::interleaveRows(encoded.data(), channels, image.width, y0, y1,
                                 *options.extra_channels, with_channels);
        data = with_channels.data();
      }
      if (data_type == OIIO::TypeDesc::UINT8) {
        bytes = quantise<std::uint8_t>(encoded);
        data = bytes.data();
      } else if (data_type == OIIO::TypeDesc::UINT16) {
        words = quantise<std::uint16_t>(encoded);
        data = words.data();
      }
      // Scanline numbers are the data window's (its origin, keepDisplayWindow, may not be 0).
      ok = checked.output().write_scanlines(spec.y + y0, spec.y + y1, 0, data_type, data);
    }
    if (ok && part_specs->size() > 1)
      ok = io_extra::writeParts(checked.output(), temp, *part_specs, *options.other_parts);
    if (!ok || !checked.close()) return failure(checked.cause());
    if (like && like->metadata) {
      return writePhotoMetadata(temp, *like->metadata, {image.width, image.height, same_encoding},
                                path, &left_out);
    }
    return Status::success();
  });
  if (written) warnMetadataLeftOut(options, path, left_out);
  return written;
}

bool imageExtensionWritable(const std::string& extension) {
  if (extension.empty() || extension.find_first_of("/.") != std::string::npos) return false;
  auto out = OIIO::ImageOutput::create("stdout." + io_text::lower(extension));
  if (!out) OIIO::geterror();  // clear the thread's pending message
  return out != nullptr;
}

}  // namespace oiio_io
}  // namespace artcam
