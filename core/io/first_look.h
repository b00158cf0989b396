// SPDX-License-Identifier: Apache-2.0
// A photo's quick first look, for the studio to show while readImage decodes the whole file:
// libjpeg's DCT-scaled decode (jpeg_decode.h) of a JPEG, the largest 1/2, 1/4 or 1/8 whose
// raster still covers 7/8 of the photo shrunk (never enlarged, aspect kept) into a box (see
// firstLookReduction), as the 8-bit
// samples the file stores, turned upright (orientation.h). Colour comes as opaque RGBA (libjpeg-
// turbo writes the fourth byte, 255), ready to be an RGBA8 picture without a pass of its own;
// grey as one channel.
//
// Only files whose whole read (image_io.h) decodes those same samples through the sRGB table
// take it: an 8-bit grey or YCbCr/RGB JPEG the codec path takes, sRGB-encoded, with no ICC
// profile or one equivalent to sRGB. So the first look's colours are the whole read's, only
// fewer pixels. Any other file (PNG, TIFF, a JPEG with an Adobe RGB profile, CMYK), or a JPEG too
// small to reduce, has no first look (nullopt): the caller reads it whole. Errors are
// readImage's (one line naming the file); the whole read would meet them too.
#pragma once

#include "core/io/stored_image.h"
#include "core/model/status.h"

#include <functional>
#include <optional>
#include <string>

namespace artcam {

struct FirstLook {
  // Upright, 8-bit sRGB: Y, or R, G, B, A with A = 255 (alpha_channel 3); info as readImage
  // gives it.
  StoredImage image;
  int reduced_by = 1;  // libjpeg's 1/n, each side rounded up
  int full_width = 0;  // the whole photo, upright
  int full_height = 0;
};

// The DCT scaling a first look of a width × height raster takes for the box: 2, 4 or 8, or 1
// when even 1/2 would not do. The raster must cover kFirstLookCover of the photo shrunk into the
// box, per side: a first look is shown at most 8/7 enlarged, only until the full photo
// replaces it, so a 6000×4000 photo takes 1/4 (1500×1000 for a 1620×1080 preview), which
// decodes faster than 1/2 and leaves a quarter of the pixels to copy. The orientation is not
// known from the header, so the raster must do so either way up.
inline constexpr double kFirstLookCover = 7.0 / 8.0;
int firstLookReduction(int width, int height, int box_width, int box_height);

// `progress` as ReadImageOptions::progress (false cancels: the read fails with "cancelled").
Result<std::optional<FirstLook>> readFirstLook(const std::string& path, int box_width,
                                               int box_height,
                                               const std::function<bool(double)>& progress = {});

}  // namespace artcam
