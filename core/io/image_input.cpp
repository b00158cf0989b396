// SPDX-License-Identifier: Apache-2.0
#include "core/io/image_input.h"

#include "core/io/image_checks.h"
#include "core/io/io_text.h"
#include "core/io/jpeg_quality.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <unistd.h>

namespace artcam::io_input {

double memoryBudgetBytes() { return artcam::memoryBudgetBytes(); }

namespace {

// The format (OpenImageIO's name) whose signature `head`, a file's first bytes, starts with;
// "" for none. Every format this build reads that has a signature is here.
std::string formatFromSignature(std::string_view head) {
  const auto starts = [&](std::string_view magic, size_t at = 0) {
    return head.size() >= at + magic.size() && head.substr(at, magic.size()) == magic;
  };
  using namespace std::string_view_literals;
  if (starts("\x89PNG\r\n\x1a\n"sv)) return "png";
  if (starts("\xff\xd8\xff"sv)) return "jpeg";
  if (starts("II*\0"sv) || starts("MM\0*"sv) || starts("II+\0"sv) || starts("MM\0+"sv))
    return "tiff";
  if (starts("\x76\x2f\x31\x01"sv)) return "openexr";
  if (starts("GIF87a"sv) || starts("GIF89a"sv)) return "gif";
  if (starts("BM"sv)) return "bmp";
  if (starts("\0\0\1\0"sv)) return "ico";
  if (starts("#?"sv)) return "hdr";  // #?RADIANCE, #?RGBE
  if (head.size() >= 2 && head[0] == 'P' &&
      ((head[1] >= '1' && head[1] <= '7') || head[1] == 'F' || head[1] == 'f'))
    return "pnm";
  if (starts("SDPX"sv) || starts("XPDS"sv)) return "dpx";
  if (starts("\x80\x2a\x5f\xd7"sv) || starts("\xd7\x5f\x2a\x80"sv)) return "cineon";
  if (starts("8BPS"sv)) return "psd";
  if (starts("RIFF"sv) && starts("WEBP"sv, 8)) return "webp";
  if (starts("ftyp"sv, 4)) return "heif";
  if (starts("\0\0\0\x0cjP  "sv) || starts("\xff\x4f\xff\x51"sv)) return "jpeg2000";
  if (starts("DDS "sv)) return "dds";
  if (starts("SIMPLE  ="sv)) return "fits";
  if (starts("\x01\xda"sv)) return "sgi";
  if (starts("\x53\x80\xf6\x34"sv)) return "softimage";
  if (starts("FOR4"sv) || starts("FORM"sv)) return "iff";
  if (starts("DICM"sv, 128)) return "dicom";
  if (starts("\xab\x67\x08\x2f"sv) || starts("\x2f\x08\x67\xab"sv)) return "zfile";
  return "";
}

// Formats whose files the table above cannot tell (Targa and RLA have no signature; camera
// raw files have many): read when the extension names them, by that reader alone. Movies are
// never read (image_checks::movieContainer says why).
bool readByExtension(const std::string& format) {
  return format == "targa" || format == "rla" || format == "raw";
}

// The format whose reader OpenImageIO registers for `extension` (no dot, any case), or "". Looked
// up in OpenImageIO's extension list rather than by ImageInput::create(extension), which, for an
// extension no reader claims, instantiates every reader it has (LibRaw's among them) to ask it.
std::string formatForExtension(std::string extension) {
  static const std::map<std::string, std::vector<std::string>> formats = OIIO::get_extension_map();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& [format, extensions] : formats)
    if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end())
      return format;
  return {};
}

// The reader for `path`, chosen before OpenImageIO opens anything: the extension's format when
// the file's first bytes are that format's signature (or it has none to tell), else the
// signature's format, else none. OpenImageIO alone would try every reader it has on a file
// its extension's reader refuses, and some crawl through all of it (100 MB of zeros named
// .png took 9 s in the DICOM reader); a file that is no format's is refused at once.
Result<OIIO::ImageInput::unique_ptr> createReader(const std::string& path) {
  using R = Result<OIIO::ImageInput::unique_ptr>;
  std::string head(512, '\0');
  if (std::FILE* file = std::fopen(path.c_str(), "rb")) {
    head.resize(std::fread(head.data(), 1, head.size(), file));
    std::fclose(file);
  } else {
    return R::failure(path + ": cannot read: " + std::strerror(errno));
  }
  if (head.empty()) return R::failure(path + ": cannot read: the file is empty");
  std::string by_extension;
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension.size() > 1) by_extension = formatForExtension(extension.substr(1));
  std::string movie = image_checks::movieContainer(head);
  if (movie.empty() && by_extension == "ffmpeg") movie = extension.substr(1);
  if (!movie.empty()) return R::failure(image_checks::movieRefusal(path, movie));
  const std::string signature = formatFromSignature(head);
  const std::string format =
      !by_extension.empty() && (by_extension == signature || readByExtension(by_extension))
          ? by_extension
          : signature;
  if (format.empty())
    return R::failure(path + ": cannot read: not an image this build reads (its first bytes " +
                      "are no image format's signature)");
  auto in = OIIO::ImageInput::create(format);
  if (!in) return R::failure(path + ": cannot read: " + io_text::oneLine(OIIO::geterror()));
  return R::success(std::move(in));
}

}  // namespace

Result<OIIO::ImageInput::unique_ptr> openImageInput(const std::string& path, bool whole) {
  using R = Result<OIIO::ImageInput::unique_ptr>;
  if (const Status file = image_checks::regularFile(path); !file) return R::failure(file.message);
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageInput::unique_ptr in;
  try {
    auto created = createReader(path);
    if (!created) return R::failure(created.status.message);
    in = std::move(*created.value);
    OIIO::ImageSpec opened;
    if (!in->open(path, opened, config)) {
      std::string cause = in->geterror();
      return R::failure(
          path + ": cannot read: " + io_text::oneLine(cause.empty() ? OIIO::geterror() : cause));
    }
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

Result<std::optional<Chromaticities>> foreignChromaticities(const OIIO::ImageSpec& spec,
                                                            const std::string& path) {
  using R = Result<std::optional<Chromaticities>>;
  const OIIO::ParamValue* attribute = spec.find_attribute("chromaticities");
  const int colours = keptChannels(spec) - (keptAlpha(spec) >= 0 ? 1 : 0);
  if (!attribute || colours < 3) return R::success(std::nullopt);
  const OIIO::TypeDesc type = attribute->type();
  if (type.basetype != OIIO::TypeDesc::FLOAT || type.numelements() * type.aggregate != 8)
    return R::success(std::nullopt);
  Chromaticities file;
  const auto* values = static_cast<const float*>(attribute->data());
  for (size_t k = 0; k < 8; ++k) file.xy[k] = values[k];
  if (!file.valid())
    return R::failure(path + ": cannot read: the chromaticities attribute (" + file.describe() +
                      ") describes no RGB colour space");
  if (file.isRec709()) return R::success(std::nullopt);
  return R::success(file);
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

// The names of a multi-part file's parts after the first (image_io.h, ImageInfo::other_parts).
std::vector<std::string> otherPartNames(const std::string& path) {
  std::vector<std::string> names;
  try {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      OIIO::geterror();  // clear the thread's pending message
      return names;
    }
    for (int part = 1; in->seek_subimage(part, 0); ++part) {
      const std::string name = in->spec().get_string_attribute("name");
      names.push_back(name.empty() ? "part " + std::to_string(part) : name);
    }
    in->geterror();  // the failed seek past the last part
  } catch (const std::exception&) {
  }
  return names;
}

}  // namespace

std::shared_ptr<const OIIO::ImageSpec> likeSpec(const ImageInfo* like) {
  if (!like) return nullptr;
  if (like->spec) return std::static_pointer_cast<const OIIO::ImageSpec>(like->spec);
  if (like->path.empty()) return nullptr;
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  try {
    // Through the reader choice of every read, never OpenImageIO's own guess by name.
    auto created = createReader(like->path);
    if (!created) return nullptr;
    OIIO::ImageInput::unique_ptr in = std::move(*created.value);
    OIIO::ImageSpec opened;
    if (!in->open(like->path, opened, config)) {
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
  if (info.format_name == "jpeg") {
    info.jpeg_quality = estimateJpegQuality(path);
    info.jpeg_subsampling = jpegSubsampling(path);
  }
  info.metadata = std::move(metadata);
  if (spec.get_int_attribute("oiio:subimages", 1) > 1) info.other_parts = otherPartNames(path);
  if (info.format_name == "openexr" && spec.full_width > 0 && spec.full_height > 0 &&
      orientation == 1) {
    info.data_origin_x = spec.x - spec.full_x;
    info.data_origin_y = spec.y - spec.full_y;
    info.display_width = spec.full_width;
    info.display_height = spec.full_height;
  }
  if (auto primaries = foreignChromaticities(spec, path); primaries)
    info.chromaticities = *primaries.value;
  for (int c = keptChannels(spec); c < spec.nchannels; ++c)
    info.dropped_channels.push_back(c < static_cast<int>(spec.channelnames.size()) &&
                                            !spec.channelnames[static_cast<size_t>(c)].empty()
                                        ? spec.channelnames[static_cast<size_t>(c)]
                                        : "channel " + std::to_string(c));
  return info;
}

}  // namespace artcam::io_input
