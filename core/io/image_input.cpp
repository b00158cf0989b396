// SPDX-License-Identifier: Apache-2.0
#include "core/io/image_input.h"

#include "core/io/image_checks.h"
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

Result<OIIO::ImageInput::unique_ptr> openImageInput(const std::string& path, bool whole) {
  using R = Result<OIIO::ImageInput::unique_ptr>;
  if (const Status file = image_checks::regularFile(path); !file) return R::failure(file.message);
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
  if (const Status size = image_checks::claimedSize(path, spec.width, spec.height, spec.nchannels,
                                                    static_cast<int>(spec.format.size()), whole);
      !size)
    return R::failure(size.message);
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

namespace {

// The spec of the photo as handed over: turned upright, saying Orientation 1.
std::shared_ptr<const OIIO::ImageSpec> uprightSpec(const OIIO::ImageSpec& spec, int orientation) {
  auto upright = std::make_shared<OIIO::ImageSpec>(spec);
  if (orientationSwapsAxes(orientation)) {
    std::swap(upright->width, upright->height);
    std::swap(upright->full_width, upright->full_height);
    std::swap(upright->x, upright->y);
    std::swap(upright->full_x, upright->full_y);
  }
  if (orientation != 1 || spec.find_attribute("Orientation")) upright->attribute("Orientation", 1);
  return upright;
}

}  // namespace

std::shared_ptr<const OIIO::ImageSpec> likeSpec(const ImageInfo* like) {
  if (!like) return nullptr;
  if (like->spec) return std::static_pointer_cast<const OIIO::ImageSpec>(like->spec);
  if (like->path.empty()) return nullptr;
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  try {
    auto in = OIIO::ImageInput::open(like->path, &config);
    if (!in) {
      OIIO::geterror();  // clear the thread's pending message
      return nullptr;
    }
    return uprightSpec(in->spec(), like->stored_orientation);
  } catch (const std::exception&) {
    return nullptr;
  }
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
  info.spec = uprightSpec(spec, orientation);
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
