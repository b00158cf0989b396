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

#include <cstdint>
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
// The pixel type readStoredImage would give `path`, from its header alone (choosing between the
// stored and the float path before decoding anything), with readStoredImage's refusals.
Result<PixelType> readStoredPixelType(const std::string& path);

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

}  // namespace artcam
