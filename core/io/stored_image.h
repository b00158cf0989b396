// SPDX-License-Identifier: Apache-2.0
// Images in the pixel type their file stores:
// 8-bit and 16-bit files stay 8/16-bit in memory, half/float files become float, so a 24 Mpix
// JPEG costs 72 MB instead of the 288 MB of a float copy (image_io.h's ImageF path).
//
// Conventions (image_view.h): values are the STORED numbers (still sRGB- or otherwise-encoded);
// a renderer interpolates them as they are, like OpenCV's remap. Alpha, when present, is made
// premultiplied in that stored domain on read (rounded to nearest for integers) and divided out
// again on write for formats that store straight alpha (everything but OpenEXR). Integer
// premultiplication loses colour precision where alpha is small: callers that need exact linear
// light (compositing, effects) use readImage/writeImage instead.
//
// Writing keeps the input's transfer, so it is only offered where the output format stores
// the same kind of number (integer→integer, float→float): storedWriteKeepsEncoding says so.
// Saves are atomic (atomic_file.h). Metadata is carried over as writeImage does.
#pragma once

#include "core/io/image_io.h"
#include "core/model/status.h"
#include "core/model/image_view.h"
#include "core/model/pixel_buffer.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace artcam {

struct StoredImage {
  PixelBuffer bytes;  // packed rows of width · channels samples of `type` (huge pages, zeroed)
  int width = 0;
  int height = 0;
  int channels = 0;        // 1..4 (further channels: readExtraChannels, image_io.h)
  int alpha_channel = -1;  // premultiplied (see above), or -1
  PixelType type = PixelType::UInt8;
  ImageInfo info;          // what the file said about itself, for writing the same kind back

  ConstImageView view() const {
    return packedView<const void>(bytes.data(), width, height, channels, type, alpha_channel);
  }
  ImageView view() {
    return packedView<void>(bytes.data(), width, height, channels, type, alpha_channel);
  }
};

// An empty image of the given shape, e.g. the output of a warp: zeroed, or left uninitialised
// for a producer that writes every byte (pixel_buffer.h says why).
StoredImage makeStoredImage(int width, int height, int channels, int alpha_channel, PixelType type,
                            PixelBuffer::Init init = PixelBuffer::Init::Zeroed);

Result<StoredImage> readStoredImage(const std::string& path, const ReadImageOptions& options = {});
// What readStoredImage would give `path`, from its header alone (choosing between the stored,
// the streamed and the float path before decoding anything): the stored raster's size (before
// any EXIF turn), the channels kept and the pixel type. readStoredImage's refusals but the
// memory budget, which depends on the path taken.
struct StoredShape {
  int width = 0, height = 0, channels = 0;
  PixelType type = PixelType::UInt8;
  // The file's RGB is in primaries other than the working space's (ImageInfo::chromaticities):
  // only an output that names its primaries (OpenEXR) may keep the stored values.
  bool foreign_primaries = false;
  // An OpenEXR whose data window is not its display window (image_io.h): only readImage with
  // ReadImageOptions::data_window takes it.
  bool data_window = false;
};
Result<StoredShape> readStoredShape(const std::string& path);

// A photo read band by band in its stored type, top to bottom, for photos too big to hold
// whole (core/pipeline/streamed_warp.h). Rows are what readStoredImage would hold: the same
// samples, alpha premultiplied the same way. Decoded by OpenImageIO scanline by scanline.
class StoredImageReader {
 public:
  // readStoredImage's refusals but the memory budget (the caller checks what it holds), and a
  // photo stored turned (EXIF Orientation other than 1: turning it upright needs every row).
  static Result<std::unique_ptr<StoredImageReader>> open(const std::string& path);
  virtual ~StoredImageReader() = default;
  StoredImageReader(const StoredImageReader&) = delete;
  StoredImageReader& operator=(const StoredImageReader&) = delete;

  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;       // 1..4, as readStoredImage keeps
  virtual int alphaChannel() const = 0;   // or -1
  virtual PixelType type() const = 0;
  virtual const ImageInfo& info() const = 0;  // as readStoredImage's image.info
  virtual int nextRow() const = 0;            // rows read so far

  // The next `count` rows into `rows`, `row_bytes` apart. Fails (one line naming the file) on
  // damage or when fewer rows are left.
  virtual Status read(int count, void* rows, std::size_t row_bytes) = 0;

 protected:
  StoredImageReader() = default;  // the codecs' readers derive from it
};

// True when writing `type` samples to `path`'s format keeps their encoding: integer samples
// into a format that stores integers, float into one that stores float/half. False also when
// the path has no known image format (writeStoredImage then says why).
bool storedWriteKeepsEncoding(const std::string& path, PixelType type);
// Whether `path`'s format stores an alpha channel (PNG, TIFF, EXR: yes; JPEG: no).
bool formatStoresAlpha(const std::string& path);

// Writes `image` to `path` in its own pixel type where the format stores it (uint16 into an
// 8-bit-only format is rescaled by OIIO), with `like`'s transfer name and metadata (may be
// null: sRGB for integers, linear for float). A format without alpha gets the premultiplied
// colour, i.e. composited over black. Fails (no file written) when the encoding would change.
Status writeStoredImage(const std::string& path, const ConstImageView& image,
                        const ImageInfo* like = nullptr, const WriteImageOptions& options = {});

// Output rows [y0, y1) for writeStoredImageBands: sets `rows` to a view of y1 − y0 rows in the
// image's layout, valid until the next call. A failure stops the write (no file is left).
using StoredBandSource = std::function<Status(int y0, int y1, ConstImageView& rows)>;
// writeStoredImage with the rows made on demand, top to bottom, in bands: `shape` gives the
// size, channels, alpha and type (its pixels are not read). Peak memory is a band, not the
// image (core/pipeline/streamed_warp.h renders each band as the encoder asks for it).
Status writeStoredImageBands(const std::string& path, const ConstImageView& shape,
                             const ImageInfo* like, const WriteImageOptions& options,
                             const StoredBandSource& band_rows);

}  // namespace artcam
