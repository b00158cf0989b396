// SPDX-License-Identifier: Apache-2.0
#include "core/depth/stereo_depth.h"

#include "core/colour/transfer.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace artcam {
namespace {

// The matcher's cost volume is width · height · disparities 16-bit costs at most (3-way SGBM
// keeps a few rows of it; HH would keep it whole): bounded so a huge pair is refused, not
// thrashed.
constexpr double kMaxCostBytes = 4.0e9;

int searchedDisparities(const StereoOptions& o, int width) {
  const int wanted = o.max_disparity > 0 ? o.max_disparity : std::min(256, std::max(16, width / 4));
  return (wanted + 15) / 16 * 16;
}

cv::Mat greyBytes(const ImageF& image) {
  cv::Mat out(image.height, image.width, CV_8UC1);
  const int colours = image.alpha_channel >= 0 ? image.channels - 1 : image.channels;
  const Transfer srgb = Transfer::srgb();
  for (int y = 0; y < image.height; ++y) {
    auto* row = out.ptr<unsigned char>(y);
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      double luminance = colours >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
      if (image.alpha_channel >= 0 && p[image.alpha_channel] > 0)
        luminance /= p[image.alpha_channel];  // straight colour: the matcher compares surfaces
      const double encoded = srgb.encode(std::clamp(luminance, 0.0, 1.0));
      row[x] = static_cast<unsigned char>(std::lround(encoded * 255.0));
    }
  }
  return out;
}

}  // namespace

Status checkStereoOptions(const StereoOptions& o, int width, int height) {
  if (!(o.baseline_focal > 0.0) || !std::isfinite(o.baseline_focal))
    return Status::failure(
        "--baseline-focal must be above 0 (the baseline in depth units times "
        "the focal length in pixels)");
  if (o.max_disparity < 0 || o.max_disparity > 1024)
    return Status::failure("--max-disparity expects a whole number from 0 to 1024");
  if (!(o.min_texture >= 0.0) || !std::isfinite(o.min_texture))
    return Status::failure("the texture threshold must be a number ≥ 0");
  if (o.block_size < 3 || o.block_size > 11 || o.block_size % 2 == 0)
    return Status::failure("--block expects an odd number from 3 to 11");
  const int d = searchedDisparities(o, width);
  if (d >= width)
    return Status::failure("--max-disparity " + std::to_string(d) + " is not below the width " +
                           std::to_string(width));
  if (static_cast<double>(width) * height * d * 2.0 > kMaxCostBytes)
    return Status::failure(std::to_string(width) + "x" + std::to_string(height) + " with " +
                           std::to_string(d) +
                           " disparities is beyond the matcher's memory "
                           "bound; scale the pair down or lower --max-disparity");
  return Status::success();
}

Result<ImageF> depthFromStereo(const ImageF& left, const ImageF& right, const StereoOptions& o,
                               StereoSummary* summary) {
  if (left.empty() || right.empty())
    return Result<ImageF>::failure("the stereo pair has an empty image");
  if (left.width != right.width || left.height != right.height)
    return Result<ImageF>::failure(
        "the pair is " + std::to_string(left.width) + "x" + std::to_string(left.height) + " and " +
        std::to_string(right.width) + "x" + std::to_string(right.height) +
        ": a rectified pair has one size");
  if (const Status s = checkStereoOptions(o, left.width, left.height); !s)
    return Result<ImageF>::failure(s.message);
  const int disparities = searchedDisparities(o, left.width);
  const int b = o.block_size;
  // Hirschmüller's smoothness penalties as OpenCV's sample sets them for one channel.
  cv::Ptr<cv::StereoSGBM> sgbm = cv::StereoSGBM::create(
      0, disparities, b, 8 * b * b, 32 * b * b, /*disp12MaxDiff=*/1, /*preFilterCap=*/63,
      /*uniquenessRatio=*/10, /*speckleWindowSize=*/100, /*speckleRange=*/2,
      cv::StereoSGBM::MODE_SGBM_3WAY);
  cv::Mat disparity;  // CV_16S, 16 × disparity; below 0: none
  cv::Mat texture;    // CV_32F: the mean |∂I/∂x| over the matcher's window, grey levels per px
  try {
    const cv::Mat grey_left = greyBytes(left);
    sgbm->compute(grey_left, greyBytes(right), disparity);
    // Where the window has no horizontal texture the cost is flat along the epipolar line and
    // the matcher only spreads its neighbours' disparities (a textureless sky takes the roof's
    // depth for tens of pixels): such pixels get none.
    if (o.min_texture > 0) {
      cv::Mat dx;
      cv::Sobel(grey_left, dx, CV_32F, 1, 0, 3, 1.0 / 8.0);
      cv::boxFilter(cv::abs(dx), texture, CV_32F, cv::Size(b, b));
    }
  } catch (const cv::Exception&) {
    return Result<ImageF>::failure("the stereo matcher failed on this pair");
  } catch (const std::bad_alloc&) {
    return Result<ImageF>::failure("not enough memory for the stereo matcher");
  }
  ImageF depth(left.width, left.height, 1);
  long long matched = 0, seen = 0;
  double zmin = std::numeric_limits<double>::infinity(), zmax = 0.0;
  double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
  for (int y = 0; y < left.height; ++y) {
    const auto* row = disparity.ptr<short>(y);
    for (int x = 0; x < left.width; ++x) {
      if (x >= disparities) ++seen;
      if (row[x] <= 0) continue;  // no match, or at infinity (no finite depth)
      if (!texture.empty() && texture.at<float>(y, x) < o.min_texture) continue;
      const double d = row[x] / 16.0;
      const double z = o.baseline_focal / d;
      *depth.pixel(x, y) = static_cast<float>(z);
      if (x >= disparities) ++matched;
      zmin = std::min(zmin, z);
      zmax = std::max(zmax, z);
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
  }
  if (zmax == 0.0)
    return Result<ImageF>::failure(
        "no pixel of the pair matched (is it rectified, and the left "
        "image first?)");
  if (summary) {
    summary->max_disparity = disparities;
    summary->matched_share = seen ? static_cast<double>(matched) / seen : 0.0;
    summary->min_depth = zmin;
    summary->max_depth = zmax;
    summary->min_disparity_px = dmin;
    summary->max_disparity_px = dmax;
  }
  return Result<ImageF>::success(std::move(depth));
}

}  // namespace artcam
