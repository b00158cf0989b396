// SPDX-License-Identifier: Apache-2.0
// libjpeg's errors arrive through error_exit, which must not return: it longjmps back to the
// setjmp of the function that entered libjpeg, whose locals are plain values (jpeg_decode.cpp
// does the same); the compressor and the file are released by the owning struct's destructor.
#include "core/io/jpeg_file.h"

#include "core/io/atomic_file.h"
#include "core/io/embedded_profile.h"
#include "core/io/image_checks.h"
#include "core/io/integer_decode.h"
#include "core/io/io_text.h"
#include "core/io/jpeg_decode.h"
#include "core/io/jpeg_quality.h"
#include "core/io/orientation.h"
#include "core/io/photo_metadata.h"

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include <jerror.h>
#include <jpeglib.h>

namespace artcam::jpeg_file {
namespace {

// The decoder for `path` when this path reads it: a regular file that is a JPEG the codec path
// decodes (8-bit grey or YCbCr/RGB). nullopt: not ours (the module reads it).
std::optional<Result<std::unique_ptr<JpegDecoder>>> openOurs(const std::string& path) {
  using R = Result<std::unique_ptr<JpegDecoder>>;
  if (!image_checks::regularFile(path) || !startsLikeJpeg(path)) return std::nullopt;
  auto decoder = JpegDecoder::open(path);
  if (!decoder) return R::failure(decoder.status.message);
  if (!(*decoder)->supported()) return std::nullopt;
  return decoder;
}

// What a JPEG written from this one carries over from its header: the JFIF density, the
// comment and the ICC profile (its EXIF, IPTC and XMP come from PhotoMetadata).
struct HeaderMarkers {
  bool jfif = false;
  unsigned char density_unit = 0;
  unsigned short x_density = 1, y_density = 1;
  std::vector<std::string> comments;
  std::vector<unsigned char> icc;
};

// libjpeg's error handling for the header reader and the compressor: error_exit formats the
// message and jumps back to the caller's setjmp; warnings and traces are dropped.
struct JumpErrors {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char fatal[JMSG_LENGTH_MAX] = {};
  int write_errno =
      0;  // a failed fwrite's errno: libjpeg's own text ("out of disk space?") guesses
  jpeg_error_mgr* install() {
    jpeg_std_error(&manager);
    manager.error_exit = [](j_common_ptr common) {
      JumpErrors* e = reinterpret_cast<JumpErrors*>(common->err);
      const int err = errno;  // the stdio destination's fwrite or fflush, before anything else
      if (common->err->msg_code == JERR_FILE_WRITE && err != 0) e->write_errno = err;
      (*common->err->format_message)(common, e->fatal);
      if (e->write_errno != 0) std::snprintf(e->fatal, sizeof e->fatal, "%s", std::strerror(err));
      std::longjmp(e->jump, 1);
    };
    manager.emit_message = [](j_common_ptr, int) {};
    return &manager;
  }
};

struct HeaderReader {
  std::FILE* file = nullptr;
  jpeg_decompress_struct info{};
  JumpErrors errors{};
  bool created = false;
  ~HeaderReader() {
    if (created) jpeg_destroy_decompress(&info);
    if (file) std::fclose(file);
  }
};

bool readMarkers(HeaderReader& r, HeaderMarkers& markers) {
  if (setjmp(r.errors.jump)) return false;
  jpeg_create_decompress(&r.info);
  r.created = true;
  jpeg_stdio_src(&r.info, r.file);
  jpeg_save_markers(&r.info, JPEG_COM, 0xFFFF);
  jpeg_save_markers(&r.info, JPEG_APP0 + 2, 0xFFFF);
  jpeg_read_header(&r.info, TRUE);
  markers.jfif = r.info.saw_JFIF_marker;
  markers.density_unit = r.info.density_unit;
  markers.x_density = r.info.X_density;
  markers.y_density = r.info.Y_density;
  for (jpeg_saved_marker_ptr m = r.info.marker_list; m; m = m->next)
    if (m->marker == JPEG_COM) {
      std::string text(reinterpret_cast<const char*>(m->data), m->data_length);
      while (!text.empty() && text.back() == '\0') text.pop_back();
      if (!text.empty()) markers.comments.push_back(std::move(text));
    }
  JOCTET* icc = nullptr;
  unsigned int icc_bytes = 0;
  if (jpeg_read_icc_profile(&r.info, &icc, &icc_bytes) && icc) {
    markers.icc.assign(icc, icc + icc_bytes);
    std::free(icc);
  }
  return true;
}

// The header markers of the JPEG `like` was read from; empty when there is none or it is gone.
HeaderMarkers markersOf(const ImageInfo* like) {
  HeaderMarkers markers;
  if (!like || like->path.empty()) return markers;
  HeaderReader r;
  r.file = std::fopen(like->path.c_str(), "rb");
  if (!r.file) return markers;
  r.info.err = r.errors.install();
  if (!readMarkers(r, markers)) return HeaderMarkers{};
  return markers;
}

struct Compressor {
  std::FILE* file = nullptr;
  jpeg_compress_struct info{};
  JumpErrors errors{};
  bool created = false;
  ~Compressor() {
    if (created) jpeg_destroy_compress(&info);
    if (file) std::fclose(file);
  }
};

bool startCompress(Compressor& c, int width, int height, int components, int quality,
                   const std::string& subsampling, const HeaderMarkers& markers) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_create_compress(&c.info);
  c.created = true;
  jpeg_stdio_dest(&c.info, c.file);
  c.info.image_width = static_cast<JDIMENSION>(width);
  c.info.image_height = static_cast<JDIMENSION>(height);
  c.info.input_components = components;
  c.info.in_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c.info);
  c.info.write_JFIF_header = TRUE;
  // jpeg_set_defaults resets the density: OpenImageIO's rule, the input's or 1:1 without unit.
  c.info.density_unit = markers.jfif ? markers.density_unit : 0;
  c.info.X_density = markers.jfif ? std::max<unsigned short>(1, markers.x_density) : 1;
  c.info.Y_density = markers.jfif ? std::max<unsigned short>(1, markers.y_density) : 1;
  jpeg_set_quality(&c.info, quality, TRUE);
  // Luma's sampling factors over chroma's 1 × 1, as OpenImageIO's writer sets them.
  if (components == 3) {
    c.info.comp_info[0].h_samp_factor = subsampling == "4:4:4" ? 1 : 2;
    c.info.comp_info[0].v_samp_factor = subsampling == "4:2:0" ? 2 : 1;
  }
  jpeg_start_compress(&c.info, TRUE);
  for (const std::string& comment : markers.comments)  // with its NUL, as OpenImageIO writes it
    jpeg_write_marker(&c.info, JPEG_COM, reinterpret_cast<const JOCTET*>(comment.c_str()),
                      static_cast<unsigned int>(comment.size() + 1));
  if (!markers.icc.empty())
    jpeg_write_icc_profile(&c.info, markers.icc.data(), static_cast<unsigned int>(markers.icc.size()));
  return true;
}

bool writeRows(Compressor& c, const unsigned char* const* rows, int count) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_write_scanlines(&c.info, const_cast<JSAMPARRAY>(rows), static_cast<JDIMENSION>(count));
  return true;
}

bool finishCompress(Compressor& c) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_finish_compress(&c.info);
  return true;
}

}  // namespace

bool startsLikeJpeg(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return false;
  unsigned char magic[3] = {};
  const size_t got = std::fread(magic, 1, 3, file);
  std::fclose(file);
  return got == 3 && magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF;
}

ImageInfo describe(const std::string& path, int stored_orientation,
                   std::shared_ptr<const PhotoMetadata> metadata) {
  ImageInfo info;
  info.path = path;
  info.format_name = "jpeg";
  info.pixel_type = "uint8";
  info.srgb = true;
  info.colour_space = "sRGB";
  info.stored_orientation = stored_orientation;
  info.jpeg_quality = estimateJpegQuality(path);
  info.jpeg_subsampling = jpegSubsampling(path);
  info.metadata = std::move(metadata);
  return info;
}

bool jpegExtension(const std::string& path) {
  const std::string e = io_text::lower(std::filesystem::path(path).extension().string());
  return e == ".jpg" || e == ".jpeg" || e == ".jpe" || e == ".jif" || e == ".jfif" || e == ".jfi";
}

std::optional<Result<StoredShape>> readShape(const std::string& path) {
  using R = Result<StoredShape>;
  auto opened = openOurs(path);
  if (!opened) return std::nullopt;
  if (!*opened) return R::failure(opened->status.message);
  const JpegDecoder& d = ***opened;
  if (const Status size = image_checks::claimedSize(path, d.width(), d.height(), d.channels(), 1, false); !size)
    return R::failure(size.message);
  return R::success(StoredShape{d.width(), d.height(), d.channels(), PixelType::UInt8});
}

namespace {

// The decode both readers share, from an opened decoder (openOurs) of a file within the memory
// budget: the stored samples, turned upright (orientation.h), with readStored's ImageInfo.
Result<StoredImage> decodeUpright(const std::string& path, std::unique_ptr<JpegDecoder> jpeg,
                                  const ReadImageOptions& options) {
  using R = Result<StoredImage>;
  const int width = jpeg->width(), height = jpeg->height(), channels = jpeg->channels();
  StoredImage image;
  try {  // every byte is decoded into, so the raster is not zeroed first
    image = makeStoredImage(width, height, channels, -1, PixelType::UInt8, PixelBuffer::Init::Uninitialised);
  } catch (const std::bad_alloc&) {
    return R::failure(path + ": cannot read: not enough memory for " + std::to_string(width) + "x" +
                      std::to_string(height) + " pixels");
  }
  const Status decoded = jpeg->decode(image.bytes.data(),
                                      static_cast<size_t>(width) * static_cast<size_t>(channels),
                                      options.progress);
  jpeg.reset();  // closes the file before the metadata reader opens it
  if (!decoded) return R::failure(decoded.message);

  std::shared_ptr<const PhotoMetadata> metadata = readPhotoMetadata(path);
  const int tagged = metadata ? photoOrientation(*metadata) : 0;
  const int orientation = validOrientation(tagged != 0 ? tagged : 1);
  if (orientation != 1) {
    const bool swap = orientationSwapsAxes(orientation);
    StoredImage upright;
    try {
      upright = makeStoredImage(swap ? height : width, swap ? width : height, channels, -1,
                                PixelType::UInt8, PixelBuffer::Init::Uninitialised);
    } catch (const std::bad_alloc&) {
      return R::failure(path + ": cannot read: not enough memory to turn " + std::to_string(width) +
                        "x" + std::to_string(height) + " pixels upright");
    }
    reorientPixels(image.bytes.data(), width, height, static_cast<size_t>(channels), orientation,
                   upright.bytes.data());
    image = std::move(upright);
  }
  image.info = describe(path, orientation, std::move(metadata));
  return R::success(std::move(image));
}

// The decoder of a JPEG this path reads whole, checked against the memory budget; nullopt when
// the file is not one it takes.
std::optional<Result<std::unique_ptr<JpegDecoder>>> openWhole(const std::string& path) {
  using R = Result<std::unique_ptr<JpegDecoder>>;
  auto opened = openOurs(path);
  if (!opened || !*opened) return opened;
  const JpegDecoder& d = ***opened;
  if (const Status size = image_checks::claimedSize(path, d.width(), d.height(), d.channels(), 1, true); !size)
    return R::failure(size.message);
  return opened;
}

}  // namespace

std::optional<Result<StoredImage>> readStored(const std::string& path, const ReadImageOptions& options) {
  using R = Result<StoredImage>;
  auto opened = openWhole(path);
  if (!opened) return std::nullopt;
  if (!*opened) return R::failure(opened->status.message);
  // The float path's decision on the embedded profile, before any pixel is decoded.
  auto profile = checkEmbeddedProfile((*opened->value)->iccProfile(), (*opened->value)->channels(),
                                      true, path);
  if (!profile) return R::failure(profile.status.message);
  Result<StoredImage> image = decodeUpright(path, std::move(*opened->value), options);
  if (image) recordEmbeddedProfile(*profile, image->info);
  if (image && options.progress) options.progress(1.0);
  return image;
}

std::optional<Result<LoadedImage>> readFloat(const std::string& path, const ReadImageOptions& options) {
  using R = Result<LoadedImage>;
  auto opened = openWhole(path);
  if (!opened) return std::nullopt;
  if (!*opened) return R::failure(opened->status.message);
  const JpegDecoder& header = ***opened;
  {  // a profile to convert through, drop or refuse is the module's (the same decision)
    auto profile = checkEmbeddedProfile(header.iccProfile(), header.channels(), true, path);
    if (!profile || profile->converting || !profile->dropped.empty()) return std::nullopt;
  }
  Result<StoredImage> stored = decodeUpright(path, std::move(*opened->value), options);
  if (!stored) return R::failure(stored.status.message);
  LoadedImage loaded;
  try {
    loaded.image = ImageF(stored->width, stored->height, stored->channels, -1);
  } catch (const std::bad_alloc&) {
    return R::failure(path + ": cannot read: not enough memory for " + std::to_string(stored->width) +
                      "x" + std::to_string(stored->height) + " pixels");
  }
  integer_decode::decode(stored->bytes.data(), loaded.image.data.size(), Transfer::srgb(), loaded.image);
  loaded.info = std::move(stored->info);
  if (options.progress) options.progress(1.0);
  return R::success(std::move(loaded));
}

std::optional<Status> writeBands(const std::string& path, const ConstImageView& shape,
                                 const ImageInfo* like, const WriteImageOptions& options,
                                 const StoredBandSource& band_rows) {
  const std::string fail = path + ": cannot write: ";
  if (!jpegExtension(path) || shape.type != PixelType::UInt8) return std::nullopt;
  if (!options.pixel_type.empty() && options.pixel_type != "uint8") return std::nullopt;
  if (options.extra_channels && !options.extra_channels->empty()) return std::nullopt;
  if (like && like->format_name != "jpeg") return std::nullopt;  // its header needs OpenImageIO
  const bool alpha = shape.alpha_channel >= 0;
  const int colours = shape.channels - (alpha ? 1 : 0);
  if (colours != 1 && colours != 3) return std::nullopt;
  if (alpha && shape.alpha_channel != colours) return std::nullopt;  // alpha last, as written
  if (shape.width < 1 || shape.height < 1) return Status::failure(fail + "the image is empty or malformed");
  constexpr int kJpegMaxSide = 65500;  // libjpeg's limit
  if (shape.width > kJpegMaxSide || shape.height > kJpegMaxSide)
    return Status::failure(fail + "JPEG stores at most 65500 pixels per side");

  HeaderMarkers markers = markersOf(like);
  // A profile that does not describe the values (embedded_profile.h) labels no output.
  if (like && !like->profile_dropped.empty()) markers.icc.clear();
  const int quality = jpegQualityFor(options, like);
  const std::string subsampling = jpegSubsamplingFor(options, like);
  std::vector<std::string> left_out;  // metadata a JPEG cannot hold (one warning)
  const Status written = writeAtomically(path, [&](const std::string& temp) {
    auto failure = [&](const std::string& message) {
      return Status::failure(fail + io_text::replaceAll(io_text::oneLine(message), temp, path));
    };
    Compressor c;
    c.file = std::fopen(temp.c_str(), "wb");
    if (!c.file) return failure("cannot create the file");
    c.info.err = c.errors.install();
    if (!startCompress(c, shape.width, shape.height, colours, quality, subsampling, markers))
      return failure(c.errors.fatal);
    // Bands of rows, each handed to libjpeg as it is (alpha dropped first where there is one).
    constexpr int kBand = 64;
    const size_t packed = static_cast<size_t>(shape.width) * static_cast<size_t>(colours);
    std::vector<unsigned char> band(alpha ? packed * kBand : 0);
    std::vector<const unsigned char*> rows(kBand);
    for (int y0 = 0; y0 < shape.height; y0 += kBand) {
      if (options.progress && !options.progress(static_cast<double>(y0) / shape.height))
        return failure("cancelled");
      const int y1 = std::min(shape.height, y0 + kBand);
      ConstImageView view;
      if (const Status produced = band_rows(y0, y1, view); !produced) return produced;
      for (int y = y0; y < y1; ++y) {
        const auto* src = static_cast<const unsigned char*>(view.row(y - y0));
        if (!alpha) {
          rows[static_cast<size_t>(y - y0)] = src;
          continue;
        }
        unsigned char* dst = band.data() + static_cast<size_t>(y - y0) * packed;
        for (int x = 0; x < shape.width; ++x)
          std::memcpy(dst + static_cast<size_t>(x) * colours, src + static_cast<size_t>(x) * shape.channels,
                      static_cast<size_t>(colours));
        rows[static_cast<size_t>(y - y0)] = dst;
      }
      if (!writeRows(c, rows.data(), y1 - y0)) return failure(c.errors.fatal);
    }
    if (!finishCompress(c)) return failure(c.errors.fatal);
    const bool closed = std::fclose(c.file) == 0;
    c.file = nullptr;
    if (!closed) return failure(std::string("cannot finish the file: ") + std::strerror(errno));
    if (like && like->metadata)
      return writePhotoMetadata(temp, *like->metadata, {shape.width, shape.height, true}, path,
                                &left_out);
    return Status::success();
  });
  if (written) warnMetadataLeftOut(options, path, left_out);
  return written;
}

}  // namespace artcam::jpeg_file
