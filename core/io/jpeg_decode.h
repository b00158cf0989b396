// SPDX-License-Identifier: Apache-2.0
// JPEG pixels decoded through libjpeg-turbo directly, for the image readers (stored_image.cpp)
// and for reduced previews. Not a reader of its own: the readers open the file through
// io_input::openImageInput first (its refusals, the memory budget, the spec and metadata that
// writes carry over) and only hand the pixel decode to this codec path; everything else, and
// any JPEG this path does not take, stays with OpenImageIO.
//
// Why: OpenImageIO 2.4's JPEG reader hands scanlines over one at a time through its own
// conversion layer, far slower than djpeg. Decoding straight into the caller's rows, several
// scanlines per call, is djpeg's own loop.
//
// Pixels: the raster as stored (no orientation applied), rows top to bottom, 8-bit samples,
// Y for one component and R, G, B for three (YCbCr or RGB files), with libjpeg's defaults
// (islow DCT, fancy upsampling), which are what OpenImageIO's reader uses too, so both give
// the same bytes. CMYK/YCCK and 12-bit files are not taken (OpenImageIO converts those).
//
// Damage: libjpeg fills a truncated or corrupt file with grey and only warns; any warning is
// treated as damage, as the OpenImageIO path does (image_input.h, decodeProblems), and fails
// the decode naming the first and counting the rest.
#pragma once

#include "core/model/status.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace artcam {

class JpegDecoder {
 public:
  // Samples: as the file stores them (Y, or R, G, B). Rgba: a three-component file as R, G,
  // B, 255, libjpeg-turbo's own conversion (JCS_EXT_RGBA), for rows that go straight into an
  // RGBA8 picture (the studio's first look) without a pass of their own.
  enum class Output { Samples, Rgba };
  // Reads the header of `path`. scale_denominator 1, 2, 4 or 8 asks libjpeg's DCT scaling for
  // a raster 1/n the size (each side rounded up), decoded in a fraction of the full time.
  // Fails (one line naming the file) when the file cannot be opened or its header is corrupt.
  static Result<std::unique_ptr<JpegDecoder>> open(const std::string& path,
                                                   int scale_denominator = 1,
                                                   Output output = Output::Samples);
  ~JpegDecoder();
  JpegDecoder(const JpegDecoder&) = delete;
  JpegDecoder& operator=(const JpegDecoder&) = delete;

  // The decoded raster's size and samples per pixel (1 or 3; 4 for Output::Rgba), valid after
  // open.
  int width() const;
  int height() const;
  int channels() const;
  // Whether this path decodes the file: 8-bit, one component (grey) or three (YCbCr/RGB);
  // Output::Rgba takes three-component files only.
  bool supported() const;
  // The ICC profile the file embeds (APP2 markers), empty when none.
  const std::vector<unsigned char>& iccProfile() const;

  // Decodes every row into `pixels` (height() rows of `row_bytes`, each at least width() ·
  // channels() bytes). `progress` gets the fraction of rows done between batches of rows and
  // may return false to cancel (the decode then fails with "cancelled"). Call once.
  Status decode(std::uint8_t* pixels, std::size_t row_bytes,
                const std::function<bool(double)>& progress = {});

  struct State;  // libjpeg's decompressor and error state (jpeg_decode.cpp)

 private:
  explicit JpegDecoder(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace artcam
