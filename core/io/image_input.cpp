// SPDX-License-Identifier: Apache-2.0
#include "core/io/image_input.h"

#include "core/io/io_text.h"
#include "core/io/jpeg_quality.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <system_error>
#include <utility>

#include <unistd.h>

namespace artcam::io_input {

double memoryBudgetBytes() { return artcam::memoryBudgetBytes(); }

Result<OIIO::ImageInput::unique_ptr> openImageInput(const std::string& path) {
  using R = Result<OIIO::ImageInput::unique_ptr>;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    return R::failure(path + ": cannot read: " +
                      (std::filesystem::exists(path, error) ? "not a file" : "no such file"));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageInput::unique_ptr in;
  try {
    in = OIIO::ImageInput::open(path, &config);
  } catch (const std::exception& e) {
    // OIIO 2.4's GIF reader throws std::length_error on a 34-byte file that starts "GIF89a"
    // (tests/core/io/test_hostile_images.cpp); a decoder's exception is a refusal like any other.
    return R::failure(path + ": cannot read: " + io_text::decoderFailure(e));
  }
  if (!in) return R::failure(path + ": cannot read: " + io_text::oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return R::failure(path + ": cannot read: the image is empty");
  if (spec.depth > 1) return R::failure(path + ": cannot read: volume images are not supported");
  // A header can claim any size; the readers allocate what it claims before decoding. No codec
  // OpenImageIO reads packs more than kMaxCompression decoded bytes into one file byte (deflate
  // peaks at 1032:1, LZW near 2700:1), so a claim beyond that is a corrupt or truncated file,
  // refused before gigabytes are asked for (a 67-byte PNG can claim 100 000 × 100 000 pixels).
  constexpr double kMaxCompression = 4096.0;
  const double decoded_bytes = static_cast<double>(spec.width) * static_cast<double>(spec.height) *
                               static_cast<double>(spec.nchannels) *
                               static_cast<double>(spec.format.size());
  const double file_bytes = static_cast<double>(std::filesystem::file_size(path, error));
  if (!error && decoded_bytes > kMaxCompression * file_bytes)
    return R::failure(path + ": cannot read: the header claims " + std::to_string(spec.width) +
                      "x" + std::to_string(spec.height) + " pixels (" +
                      std::to_string(static_cast<long long>(decoded_bytes / 1e6)) +
                      " MB decoded) but the file holds only " +
                      std::to_string(static_cast<long long>(file_bytes)) +
                      " bytes (corrupt or truncated)");
  // The padding above cannot buy memory: whatever the file's size, the photo as the engine holds
  // it (float, at least the 4 channels of a render) must fit the memory budget, checked here from
  // the header before any pixel is allocated.
  const double float_bytes = static_cast<double>(spec.width) * static_cast<double>(spec.height) *
                             std::max(4.0, static_cast<double>(spec.nchannels)) * 4.0;
  const double budget = memoryBudgetBytes();
  if (float_bytes > budget) {
    const auto gib = [](double b) {
      char text[32];
      if (b < 1024.0 * 1024.0 * 1024.0)
        std::snprintf(text, sizeof text, "%.1f MiB", b / (1024.0 * 1024.0));
      else
        std::snprintf(text, sizeof text, "%.1f GiB", b / (1024.0 * 1024.0 * 1024.0));
      return std::string(text);
    };
    return R::failure(path + ": cannot read: " + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + " pixels need " + gib(float_bytes) +
                      " as float, more than the memory budget of " + gib(budget) +
                      " (half this machine's memory; ARTCAM_MAX_MEMORY_MB sets it)");
  }
  return R::success(std::move(in));
}

Result<std::unique_ptr<JpegDecoder>> jpegCodecPath(const OIIO::ImageInput& in,
                                                   const OIIO::ImageSpec& spec,
                                                   const std::string& path) {
  using R = Result<std::unique_ptr<JpegDecoder>>;
  if (std::string(in.format_name()) != "jpeg" || spec.format != OIIO::TypeDesc::UINT8)
    return R::success(nullptr);
  auto decoder = JpegDecoder::open(path);
  if (!decoder) return R::failure(decoder.status.message);
  const JpegDecoder& d = **decoder;
  if (!d.supported() || d.width() != spec.width || d.height() != spec.height ||
      d.channels() != keptChannels(spec))
    return R::success(nullptr);
  return decoder;
}

int storedOrientation(const OIIO::ImageSpec& spec, const PhotoMetadata* metadata) {
  if (metadata)
    if (const int tagged = photoOrientation(*metadata); tagged != 0)
      return validOrientation(tagged);
  return validOrientation(spec.get_int_attribute("Orientation", 1));
}

ImageInfo describeImage(const OIIO::ImageInput& in, const OIIO::ImageSpec& spec,
                        const std::string& path, const std::string& pixel_type,
                        const Transfer& transfer, int orientation,
                        std::shared_ptr<const PhotoMetadata> metadata) {
  ImageInfo info;
  info.path = path;
  info.format_name = in.format_name();
  info.pixel_type = pixel_type;
  info.srgb = transfer.kind == Transfer::Kind::Srgb;
  info.colour_space = transfer.colourSpaceName();
  info.stored_orientation = orientation;
  auto upright = std::make_shared<OIIO::ImageSpec>(spec);
  if (orientationSwapsAxes(info.stored_orientation)) {
    std::swap(upright->width, upright->height);
    std::swap(upright->full_width, upright->full_height);
    std::swap(upright->x, upright->y);
    std::swap(upright->full_x, upright->full_y);
  }
  if (orientation != 1 || spec.find_attribute("Orientation")) upright->attribute("Orientation", 1);
  info.spec = std::move(upright);
  if (info.format_name == "jpeg") info.jpeg_quality = estimateJpegQuality(path);
  info.metadata = std::move(metadata);
  for (int c = keptChannels(spec); c < spec.nchannels; ++c)
    info.dropped_channels.push_back(c < static_cast<int>(spec.channelnames.size()) &&
                                            !spec.channelnames[static_cast<size_t>(c)].empty()
                                        ? spec.channelnames[static_cast<size_t>(c)]
                                        : "channel " + std::to_string(c));
  return info;
}

}  // namespace artcam::io_input
