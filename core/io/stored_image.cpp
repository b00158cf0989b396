// SPDX-License-Identifier: Apache-2.0
// Stored-type image read/write through OpenImageIO 2.4 (stored_image.h). Like image_io.cpp,
// files are opened with "oiio:UnassociatedAlpha" = 1 so OIIO hands over the stored values and
// we premultiply ourselves; writes go through a band of rows so no whole-image copy is made.
#include "core/io/stored_image.h"
#include "core/io/format_choices.h"
#include "core/io/heif_write.h"
#include "core/io/oiio_io.h"

#include "core/colour/transfer.h"
#include "core/io/atomic_file.h"
#include "core/io/checked_output.h"
#include "core/io/embedded_profile.h"
#include "core/io/extra_channels.h"
#include "core/io/image_input.h"
#include "core/io/io_text.h"
#include "core/io/jpeg_decode.h"
#include "core/io/jpeg_segments.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>

namespace artcam {

namespace {

using io_text::decoderFailure;
using io_text::oneLine;

OIIO::TypeDesc oiioType(PixelType t) {
  switch (t) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::UInt16: return OIIO::TypeDesc::UINT16;
    case PixelType::Float: break;
  }
  return OIIO::TypeDesc::FLOAT;
}

// What the file stores, as the engine's pixel types (half is read as float).
PixelType storedType(OIIO::TypeDesc t, std::string& name) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8: name = "uint8"; return PixelType::UInt8;
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16: name = "uint16"; return PixelType::UInt16;
    case OIIO::TypeDesc::HALF: name = "half"; return PixelType::Float;
    default: name = "float"; return PixelType::Float;
  }
}

// Our progress callback (false: cancel) as OIIO's (true: stop), for reads and writes.
struct CancelHook {
  const std::function<bool(double)>& progress;
  bool cancelled = false;
  OIIO::ProgressCallback callback() const {
    if (!progress) return nullptr;
    return +[](void* opaque, float done) {
      auto* hook = static_cast<CancelHook*>(opaque);
      if (!hook->progress(static_cast<double>(done))) hook->cancelled = true;
      return hook->cancelled;
    };
  }
};

// Formats that store only 8-bit integers / only float (image_write.cpp's fitPixelType).
bool integerOnlyFormat(const std::string& f) {
  static const std::set<std::string> k{"jpeg", "bmp", "targa", "gif", "webp", "ico", "heif", "png", "pnm"};
  return k.count(f) > 0;
}
bool floatOnlyFormat(const std::string& f) { return f == "openexr" || f == "hdr"; }

// The same rule as image_write.cpp: metadata that still describes the written file.
bool keepAttribute(const std::string& name, bool same_format) {
  const std::string n = io_text::lower(name);
  if (n == "compression" || n == "compressionquality") return same_format;
  if (n.rfind("thumbnail_", 0) == 0 || n == "planarconfig") return false;
  if (n == "exif:pixelxdimension" || n == "exif:pixelydimension") return false;
  const size_t colon = n.find(':');
  if (colon == std::string::npos) return true;
  static const std::set<std::string> kPortable{"exif", "gps", "iptc", "xmp", "photoshop"};
  return kPortable.count(n.substr(0, colon)) > 0;
}

// Colour times alpha in the stored domain, rounded to nearest for integers.
template <class T>
void premultiplyRow(T* p, std::size_t count, int c_n, int a_i) {
  const float full = pixelTypeFullScale(std::is_same_v<T, std::uint8_t>    ? PixelType::UInt8
                                        : std::is_same_v<T, std::uint16_t> ? PixelType::UInt16
                                                                           : PixelType::Float);
  for (std::size_t k = 0; k < count; ++k, p += c_n) {
    const float a = static_cast<float>(p[a_i]) / full;
    for (int c = 0; c < c_n; ++c) {
      if (c == a_i) continue;
      if constexpr (std::is_floating_point_v<T>) p[c] = p[c] * a;
      else p[c] = static_cast<T>(std::lround(static_cast<float>(p[c]) * a));
    }
  }
}

template <class T>
void premultiplyRows(StoredImage& image) {
  premultiplyRow(static_cast<T*>(static_cast<void*>(image.bytes.data())),
                 static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
                 image.channels, image.alpha_channel);
}

// One row of the view → the written layout: alpha dropped (composited over black) or colour
// divided by alpha (straight-alpha formats).
template <class T>
void unpremultiplyRow(const T* in, T* out, int width, int in_channels, int alpha, bool keep_alpha,
                      float full) {
  for (int x = 0; x < width; ++x, in += in_channels) {
    const float a = alpha >= 0 ? static_cast<float>(in[alpha]) : full;
    for (int c = 0; c < in_channels; ++c) {
      if (c == alpha) {
        if (keep_alpha) *out++ = in[c];
        continue;
      }
      if (!keep_alpha || a >= full) {
        *out++ = in[c];
      } else if (!(a > 0.0f)) {
        *out++ = T(0);
      } else {
        const float v = static_cast<float>(in[c]) * full / a;
        if constexpr (std::is_floating_point_v<T>) *out++ = v;
        else *out++ = static_cast<T>(std::min(full, std::floor(v + 0.5f)));
      }
    }
  }
}

}  // namespace

namespace oiio_io {

Result<StoredImage> readStoredImage(const std::string& path, const ReadImageOptions& options) {
  using R = Result<StoredImage>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  const OIIO::ImageInput::unique_ptr& in = *opened;
  const OIIO::ImageSpec spec = in->spec();
  if (const Status windows = io_input::dataWindowIsDisplayWindow(*in, spec, path); !windows)
    return R::failure(windows.message);
  const int channels = io_input::keptChannels(spec);
  const int alpha = io_input::keptAlpha(spec);

  std::string pixel_type;
  const PixelType type = storedType(io_input::keptFormat(spec), pixel_type);
  const Transfer transfer =
      Transfer::fromColourSpace(spec.get_string_attribute("oiio:ColorSpace"))
          .value_or(type == PixelType::Float ? Transfer::linear() : Transfer::srgb());
  const bool associated = alpha >= 0 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
  // The float path's decision on the embedded profile, before any pixel is decoded.
  auto profile =
      checkEmbeddedProfile(io_input::embeddedProfileBytes(spec), channels - (alpha >= 0 ? 1 : 0),
                           std::string(in->format_name()) == "jpeg", path);
  if (!profile) return R::failure(profile.status.message);

  // The codec path for JPEG (jpeg_decode.h): libjpeg-turbo straight into the rows, every byte
  // written, so the raster is not zeroed first. OpenImageIO decodes what that path does not take.
  auto codec = io_input::jpegCodecPath(*in, spec, path);
  if (!codec) return R::failure(codec.status.message);
  std::unique_ptr<JpegDecoder> jpeg = std::move(*codec.value);

  StoredImage image;
  // A giant header must not turn into a giant allocation by surprise: size_t arithmetic, and a
  // clear message when the allocation fails.
  try {
    image = makeStoredImage(spec.width, spec.height, channels, alpha, type,
                            jpeg ? PixelBuffer::Init::Uninitialised : PixelBuffer::Init::Zeroed);
  } catch (const std::bad_alloc&) {
    return R::failure(path + ": cannot read: not enough memory for " + std::to_string(spec.width) +
                      "x" + std::to_string(spec.height) + " pixels");
  }
  CancelHook context{options.progress};
  const OIIO::ProgressCallback callback = context.callback();
  bool ok = true;
  try {
    if (jpeg) {
      const Status decoded = jpeg->decode(
          image.bytes.data(),
          static_cast<size_t>(image.width) * static_cast<size_t>(channels), options.progress);
      jpeg.reset();  // closes the file before the metadata reader opens it
      if (!decoded) return R::failure(decoded.message);
    } else if (spec.tile_width > 0) {
      ok = in->read_image(0, 0, 0, channels, oiioType(type), image.bytes.data(), OIIO::AutoStride,
                          OIIO::AutoStride, OIIO::AutoStride, callback, &context);
    } else {
      // Bands of scanlines straight into the image: OIIO's read_image decodes a JPEG into a
      // whole-image buffer of its own first (measured +65 MiB for 24 Mpix).
      constexpr int kBand = 64;
      const size_t row_bytes = static_cast<size_t>(image.width) * static_cast<size_t>(channels) *
                               static_cast<size_t>(pixelTypeSize(type));
      for (int y = 0; ok && y < spec.height && !context.cancelled; y += kBand) {
        const int y1 = std::min(spec.height, y + kBand);
        ok = in->read_scanlines(0, 0, spec.y + y, spec.y + y1, 0, 0, channels, oiioType(type),
                                image.bytes.data() + static_cast<size_t>(y) * row_bytes);
        if (callback) callback(&context, static_cast<float>(y1) / static_cast<float>(spec.height));
      }
    }
  } catch (const std::exception& e) {  // a decoder's exception (see image_input.cpp)
    return R::failure(path + ": cannot read: " + decoderFailure(e));
  }
  if (context.cancelled) return R::failure(path + ": cannot read: cancelled");
  if (!ok) return R::failure(path + ": cannot read: " + oneLine(in->geterror()));
  if (const Status damage = io_input::decodeProblems(*in, path); !damage)
    return R::failure(damage.message);
  in->close();
  if (alpha >= 0 && !associated) {
    switch (type) {
      case PixelType::UInt8: premultiplyRows<std::uint8_t>(image); break;
      case PixelType::UInt16: premultiplyRows<std::uint16_t>(image); break;
      case PixelType::Float: premultiplyRows<float>(image); break;
    }
  }
  // Upright here too (orientation.h), so `artcam warp`'s stored path and the float path render
  // the same photo. The turn needs a second buffer of the input's size for a moment; a warp
  // holds input + output anyway, so the peak grows only when the output is smaller.
  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int orientation = io_input::storedOrientation(spec, metadata.get());
  if (orientation != 1) {
    const bool swap = orientationSwapsAxes(orientation);
    StoredImage upright;
    try {
      upright = makeStoredImage(swap ? image.height : image.width,
                                swap ? image.width : image.height, channels, alpha, type,
                                PixelBuffer::Init::Uninitialised);  // reorientPixels writes all
    } catch (const std::bad_alloc&) {
      return R::failure(path + ": cannot read: not enough memory to turn " +
                        std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        " pixels upright");
    }
    reorientPixels(image.bytes.data(), image.width, image.height,
                   static_cast<size_t>(channels) * static_cast<size_t>(pixelTypeSize(type)),
                   orientation, upright.bytes.data());
    image = std::move(upright);
  }
  image.info = io_input::describeImage(*in, spec, path, pixel_type, transfer, orientation,
                                       std::move(metadata));
  recordEmbeddedProfile(*profile, image.info);
  if (options.progress) options.progress(1.0);
  return R::success(std::move(image));
}

// The reader of every format OpenImageIO decodes, scanline by scanline (or tile row by tile row).
class OiioStoredImageReader final : public StoredImageReader {
 public:
  std::string path;
  OIIO::ImageInput::unique_ptr in;
  OIIO::ImageSpec spec;
  int channels_ = 0, alpha = -1;
  PixelType type_ = PixelType::UInt8;
  bool premultiply = false;
  int next = 0;
  ImageInfo info_;

  int width() const override { return spec.width; }
  int height() const override { return spec.height; }
  int channels() const override { return channels_; }
  int alphaChannel() const override { return alpha; }
  PixelType type() const override { return type_; }
  const ImageInfo& info() const override { return info_; }
  int nextRow() const override { return next; }
  Status read(int count, void* rows, std::size_t row_bytes) override;
};

Result<std::unique_ptr<StoredImageReader>> openStoredImageReader(const std::string& path) {
  using R = Result<std::unique_ptr<StoredImageReader>>;
  auto opened = io_input::openImageInput(path, /*whole=*/false);
  if (!opened) return R::failure(opened.status.message);
  auto state = std::make_unique<OiioStoredImageReader>();
  state->path = path;
  state->in = std::move(*opened.value);
  state->spec = state->in->spec();
  const OIIO::ImageSpec& spec = state->spec;
  if (const Status windows = io_input::dataWindowIsDisplayWindow(*state->in, spec, path); !windows)
    return R::failure(windows.message);
  state->channels_ = io_input::keptChannels(spec);
  state->alpha = io_input::keptAlpha(spec);
  std::string pixel_type;
  state->type_ = storedType(io_input::keptFormat(spec), pixel_type);
  const Transfer transfer =
      Transfer::fromColourSpace(spec.get_string_attribute("oiio:ColorSpace"))
          .value_or(state->type_ == PixelType::Float ? Transfer::linear() : Transfer::srgb());
  state->premultiply = state->alpha >= 0 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int orientation = io_input::storedOrientation(spec, metadata.get());
  if (orientation != 1)
    return R::failure(path + ": cannot read in bands: the photo is stored turned (EXIF Orientation " +
                      std::to_string(orientation) + ") and turning it upright needs every row at once");
  auto profile = checkEmbeddedProfile(io_input::embeddedProfileBytes(spec),
                                      state->channels_ - (state->alpha >= 0 ? 1 : 0),
                                      std::string(state->in->format_name()) == "jpeg", path);
  if (!profile) return R::failure(profile.status.message);
  state->info_ = io_input::describeImage(*state->in, spec, path, pixel_type, transfer, orientation,
                                         std::move(metadata));
  recordEmbeddedProfile(*profile, state->info_);
  return R::success(std::move(state));
}

Status OiioStoredImageReader::read(int count, void* rows, std::size_t row_bytes) {
  OiioStoredImageReader& st = *this;
  if (count < 0 || st.next + count > st.spec.height)
    return Status::failure(path + ": cannot read rows " + std::to_string(st.next) + "+" +
                           std::to_string(count) + ": the image has " +
                           std::to_string(st.spec.height));
  if (count == 0) return Status::success();
  bool ok = true;
  try {
    if (st.spec.tile_width > 0)
      ok = st.in->read_tiles(0, 0, st.spec.x, st.spec.x + st.spec.width, st.spec.y + st.next,
                             st.spec.y + st.next + count, 0, 1, 0, st.channels_, oiioType(st.type_),
                             rows, OIIO::AutoStride, static_cast<OIIO::stride_t>(row_bytes));
    else
      ok = st.in->read_scanlines(0, 0, st.spec.y + st.next, st.spec.y + st.next + count, 0, 0,
                                 st.channels_, oiioType(st.type_), rows, OIIO::AutoStride,
                                 static_cast<OIIO::stride_t>(row_bytes));
  } catch (const std::exception& e) {
    return Status::failure(path + ": cannot read: " + decoderFailure(e));
  }
  if (!ok) return Status::failure(path + ": cannot read: " + oneLine(st.in->geterror()));
  if (const Status damage = io_input::decodeProblems(*st.in, path); !damage) return damage;
  if (st.premultiply) {
    for (int r = 0; r < count; ++r) {
      void* row = static_cast<std::uint8_t*>(rows) + static_cast<std::size_t>(r) * row_bytes;
      switch (st.type_) {
        case PixelType::UInt8: premultiplyRow(static_cast<std::uint8_t*>(row), st.spec.width, st.channels_, st.alpha); break;
        case PixelType::UInt16: premultiplyRow(static_cast<std::uint16_t*>(row), st.spec.width, st.channels_, st.alpha); break;
        case PixelType::Float: premultiplyRow(static_cast<float*>(row), st.spec.width, st.channels_, st.alpha); break;
      }
    }
  }
  st.next += count;
  return Status::success();
}

Result<StoredShape> readStoredShape(const std::string& path) {
  auto opened = io_input::openImageInput(path, /*whole=*/false);
  if (!opened) return Result<StoredShape>::failure(opened.status.message);
  const OIIO::ImageSpec& spec = (*opened)->spec();
  // Reported, not refused: the readers refuse (or, asked to, keep) the data window.
  const bool overscan = !io_input::dataWindowIsDisplayWindow(**opened, spec, path);
  std::string name;
  const auto primaries = io_input::foreignChromaticities(spec, path);
  if (!primaries) return Result<StoredShape>::failure(primaries.status.message);
  return Result<StoredShape>::success(
      StoredShape{spec.width, spec.height, io_input::keptChannels(spec),
                  storedType(spec.format, name), primaries.value->has_value(), overscan});
}

bool storedWriteKeepsEncoding(const std::string& path, PixelType type) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) {
    OIIO::geterror();
    return false;
  }
  const std::string format = out->format_name();
  return type == PixelType::Float ? !integerOnlyFormat(format) : !floatOnlyFormat(format);
}

bool formatStoresAlpha(const std::string& path) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) {
    OIIO::geterror();
    return false;
  }
  return out->supports("alpha") != 0;
}

Status writeStoredImage(const std::string& path, const ConstImageView& image, const ImageInfo* like,
                        const WriteImageOptions& options) {
  return oiio_io::writeStoredImageBands(path, image, like, options,
                               [&image](int y0, int y1, ConstImageView& rows) {
                                 rows = image;
                                 rows.data = image.row(y0);
                                 rows.height = y1 - y0;
                                 return Status::success();
                               });
}

Status writeStoredImageBands(const std::string& path, const ConstImageView& shape,
                             const ImageInfo* like, const WriteImageOptions& options,
                             const StoredBandSource& band_rows) {
  const std::string fail = path + ": cannot write: ";
  const ConstImageView& image = shape;  // its size, channels and type; rows come from band_rows
  if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > 4 ||
      image.alpha_channel >= image.channels)
    return Status::failure(fail + "the image is empty or malformed");
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) {
    OIIO::geterror();
    const std::string extension = std::filesystem::path(path).extension().string();
    return Status::failure(path + (extension.empty()
                                       ? ": no file extension to choose an image format from"
                                       : ": no image format for extension \"" + extension + "\""));
  }
  const std::string format = out->format_name();
  if (!oiio_io::storedWriteKeepsEncoding(path, image.type))
    return Status::failure(fail + "the " + format + " format cannot store these " +
                           (image.type == PixelType::Float ? "float" : "integer") +
                           " samples without re-encoding them");
  // This path writes the samples it holds; another pixel type goes through writeImage.
  const char* held = image.type == PixelType::UInt8    ? "uint8"
                     : image.type == PixelType::UInt16 ? "uint16"
                     : like && like->pixel_type == "half" ? "half"
                                                          : "float";
  if (!options.pixel_type.empty() && options.pixel_type != held)
    return Status::failure(fail + "the stored-type writer cannot change " + held + " samples to " +
                           options.pixel_type);
  constexpr int kJpegMaxSide = 65500;  // libjpeg's limit; OIIO 2.4 would exit() past it
  if (format == "jpeg" && (image.width > kJpegMaxSide || image.height > kJpegMaxSide))
    return Status::failure(fail + "JPEG stores at most 65500 pixels per side");

  const bool keep_alpha = image.alpha_channel >= 0 && out->supports("alpha");
  const bool associated = format == "openexr";
  const int channels = image.channels - (image.alpha_channel >= 0 && !keep_alpha ? 1 : 0);
  const int alpha = keep_alpha ? image.alpha_channel : -1;
  OIIO::TypeDesc file_type = oiioType(image.type);
  if (image.type == PixelType::UInt16 && format != "png" && format != "pnm" && integerOnlyFormat(format))
    file_type = OIIO::TypeDesc::UINT8;
  if (image.type == PixelType::Float && like && like->pixel_type == "half") file_type = OIIO::TypeDesc::HALF;

  OIIO::ImageSpec spec(image.width, image.height, channels, file_type);
  const std::shared_ptr<const OIIO::ImageSpec> like_spec_held = io_input::likeSpec(like);
  const OIIO::ImageSpec* like_spec = like_spec_held.get();
  if (like_spec) {
    for (const OIIO::ParamValue& p : like_spec->extra_attribs)
      if (keepAttribute(p.name().string(), like->format_name == format)) spec.extra_attribs.push_back(p);
    // A profile that does not describe the values (embedded_profile.h) labels no output.
    if (!like->profile_dropped.empty()) spec.erase_attribute("ICCProfile");
  }
  // `like`'s names for the channels the image kept of it (its colour and alpha).
  const bool like_names = like_spec && io_input::keptChannels(*like_spec) == channels &&
                          io_input::keptAlpha(*like_spec) == alpha &&
                          static_cast<int>(like_spec->channelnames.size()) >= channels;
  if (like_names) {
    spec.channelnames.assign(like_spec->channelnames.begin(),
                             like_spec->channelnames.begin() + channels);
  } else {
    spec.channelnames.clear();
    const int colours = channels - (alpha >= 0 ? 1 : 0);
    const char* rgb[] = {"R", "G", "B"};
    for (int c = 0, k = 0; c < channels; ++c)
      spec.channelnames.emplace_back(c == alpha ? "A" : colours == 1 ? "Y" : rgb[std::min(k++, 2)]);
  }
  spec.alpha_channel = alpha;
  io_extra::keepDisplayWindow(spec, format, like_spec);
  if (const Status extra = io_extra::addExtraChannels(spec, format, options.extra_channels, path);
      !extra)
    return extra;
  const bool with_extra = options.extra_channels && !options.extra_channels->empty();
  // The values keep `like`'s encoding: its profile, when it had one, is the whole label (no PNG
  // sRGB or gAMA chunk beside it), else its transfer's name.
  const std::optional<Transfer> like_transfer =
      like ? Transfer::fromColourSpace(like->colour_space) : std::nullopt;
  if (like && like->icc)
    spec.erase_attribute("oiio:ColorSpace");
  else
    spec.attribute("oiio:ColorSpace", like_transfer        ? like_transfer->colourSpaceName()
                                      : like && like->srgb ? std::string("sRGB")
                                      : like               ? like->colour_space
                                      : image.type == PixelType::Float ? "Linear"
                                                                       : "sRGB");
  if (alpha >= 0 && !associated) spec.attribute("oiio:UnassociatedAlpha", 1);
  std::vector<std::string> left_out;  // metadata the output cannot hold (one warning)
  io_format::setFormatChoices(spec, format, options, like, like_spec);
  if (format == "jpeg") left_out = io_jpeg::fitJpegSegments(spec);

  // Straight through when the layout is already the file's; else bands of rows converted.
  const bool direct = channels == image.channels && (alpha < 0 || associated) && !with_extra;
  const int sample = pixelTypeSize(image.type);
  // A multi-part OpenEXR's later parts, after the image's (extra_channels.h).
  auto part_specs = io_extra::partSpecs(spec, format, options.other_parts, path);
  if (!part_specs) return part_specs.status;
  const Status written = writeAtomically(path, [&](const std::string& temp) {
    auto failure = [&](const std::string& message) {
      return Status::failure(fail + io_text::replaceAll(oneLine(message), temp, path));
    };
    if (io_heif::writesHeif(format) && image.type == PixelType::UInt8) {
      // Through libheif with the metadata (heif_write.h): the bands unpremultiplied as below.
      const size_t row = static_cast<size_t>(image.width) * static_cast<size_t>(channels);
      std::vector<std::uint8_t> all(row * static_cast<size_t>(image.height));
      for (int y0 = 0; y0 < image.height; y0 += 64) {
        if (options.progress && !options.progress(static_cast<double>(y0) / image.height))
          return failure("cancelled");
        const int y1 = std::min(image.height, y0 + 64);
        ConstImageView rows;
        if (const Status produced = band_rows(y0, y1, rows); !produced) return produced;
        for (int y = y0; y < y1; ++y)
          unpremultiplyRow(static_cast<const std::uint8_t*>(rows.row(y - y0)),
                           all.data() + static_cast<size_t>(y) * row, image.width, image.channels,
                           image.alpha_channel, keep_alpha, 255.0f);
      }
      io_heif::HeifImage heif{image.width, image.height, channels, alpha >= 0, all.data(), {}};
      return io_heif::writeHeifPhoto(temp, path, std::move(heif), &spec, options.jpeg_quality,
                                     like ? like->metadata.get() : nullptr,
                                     {image.width, image.height, true}, left_out);
    }
    io_checked::CheckedWrite checked(std::move(out));
    if (!checked.open(temp, *part_specs)) return failure(checked.cause());
    bool ok = true;
    CancelHook context{options.progress};  // cancel between bands
    const OIIO::ProgressCallback callback = context.callback();
    // Bands of rows from the source, each written straight through when the layout is the
    // file's, else converted (alpha dropped or divided out, extra channels interleaved) into a
    // band buffer first.
    constexpr int kBand = 64;
    const size_t row_bytes = static_cast<size_t>(image.width) * static_cast<size_t>(channels) *
                             static_cast<size_t>(sample);
    std::vector<std::uint8_t> band(direct ? 0 : row_bytes * kBand);
    std::vector<float> with_channels;
    const float full = pixelTypeFullScale(image.type);
    // OpenEXR stores premultiplied alpha: copied (it comes here only with extra channels).
    const int divided_alpha = associated ? -1 : image.alpha_channel;
    for (int y0 = 0; ok && y0 < image.height; y0 += kBand) {
      if (callback && callback(&context, static_cast<float>(y0) / static_cast<float>(image.height)))
        break;
      const int y1 = std::min(image.height, y0 + kBand);
      ConstImageView rows;
      if (const Status produced = band_rows(y0, y1, rows); !produced) return produced;
      // Scanline numbers are the data window's (its origin, keepDisplayWindow, may not be 0).
      if (direct) {
        ok = checked.output().write_scanlines(spec.y + y0, spec.y + y1, 0, oiioType(image.type),
                                              rows.data, OIIO::AutoStride, rows.row_bytes);
        continue;
      }
      for (int y = y0; y < y1; ++y) {
        void* dst = band.data() + static_cast<size_t>(y - y0) * row_bytes;
        const void* src = rows.row(y - y0);
        switch (image.type) {
          case PixelType::UInt8:
            unpremultiplyRow(static_cast<const std::uint8_t*>(src), static_cast<std::uint8_t*>(dst),
                             image.width, image.channels, divided_alpha, keep_alpha, full);
            break;
          case PixelType::UInt16:
            unpremultiplyRow(static_cast<const std::uint16_t*>(src), static_cast<std::uint16_t*>(dst),
                             image.width, image.channels, divided_alpha, keep_alpha, full);
            break;
          case PixelType::Float:
            unpremultiplyRow(static_cast<const float*>(src), static_cast<float*>(dst),
                             image.width, image.channels, divided_alpha, keep_alpha, full);
            break;
        }
      }
      // Extra channels go with OpenEXR only, so with float samples.
      const void* data = band.data();
      if (with_extra) {
        io_extra::interleaveRows(reinterpret_cast<const float*>(band.data()), channels,
                                 image.width, y0, y1, *options.extra_channels, with_channels);
        data = with_channels.data();
      }
      ok =
          checked.output().write_scanlines(spec.y + y0, spec.y + y1, 0, oiioType(image.type), data);
    }
    if (context.cancelled) return failure("cancelled");
    if (ok && part_specs->size() > 1)
      ok = io_extra::writeParts(checked.output(), temp, *part_specs, *options.other_parts);
    if (!ok || !checked.close()) return failure(checked.cause());
    // The transfer is the input's (see above), so the colour-space tags still hold.
    if (like && like->metadata)
      return writePhotoMetadata(temp, *like->metadata, {image.width, image.height, true}, path,
                                &left_out);
    return Status::success();
  });
  if (written) warnMetadataLeftOut(options, path, left_out);
  return written;
}

}  // namespace oiio_io
}  // namespace artcam
