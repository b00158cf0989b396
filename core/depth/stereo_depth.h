// SPDX-License-Identifier: Apache-2.0
// Depth from a rectified stereo pair: the paper notes (Sec. 3, with Fig 3) that the painted
// depth planes "could be removed using stereopsis". OpenCV's semi-global matcher (Hirschmüller's
// SGM, `cv::StereoSGBM`, 3-way) finds each left pixel's disparity to 1/16 px with a left-right
// check; depth is baseline·focal / disparity, the convention of the depth file reader
// (core/io/depth_file.h), and 0 where the matcher found none (occlusions, the left band no
// right pixel sees, textureless sky), never NaN.
#pragma once

#include "core/model/image.h"
#include "core/model/status.h"

namespace artcam {

struct StereoOptions {
  // Depth = baseline_focal / disparity: the baseline in depth units times the focal length in
  // pixels (the rectified pair's). Required, above 0.
  double baseline_focal = 0.0;
  // Disparities searched, 0 … max_disparity px (rounded up to a multiple of 16, OpenCV's unit);
  // 0: a quarter of the width, at most 256.
  int max_disparity = 0;
  int block_size = 5;  // odd, 3 … 11: the matcher's window
  // A pixel whose window in the left image has less horizontal texture than this (the mean
  // |∂I/∂x| of its 8-bit grey, levels per pixel) gets no depth: the matcher cannot place it and
  // would spread its neighbours' disparities over it. 0: keep every match.
  double min_texture = 0.2;
};

struct StereoSummary {
  int max_disparity = 0;       // searched (after rounding)
  double matched_share = 0.0;  // of the pixels right of the unseen band
  double min_depth = 0.0, max_depth = 0.0;
  double min_disparity_px = 0.0, max_disparity_px = 0.0;
};

// Checks the options (one line naming the cause, in the CLI's words for its options).
Status checkStereoOptions(const StereoOptions& options, int width, int height);

// The depth of every left pixel (1 channel, the left image's size) from linear-light images of
// equal size (any channel count; matched on their luminance, sRGB-encoded to 8 bits as the
// matcher's cost expects). Fails for unequal sizes, bad options or an image the matcher's
// memory (width · height · disparities) would not fit.
Result<ImageF> depthFromStereo(const ImageF& left, const ImageF& right,
                               const StereoOptions& options, StereoSummary* summary = nullptr);

}  // namespace artcam
