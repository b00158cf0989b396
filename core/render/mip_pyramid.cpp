// SPDX-License-Identifier: Apache-2.0
#include "core/render/mip_pyramid.h"

#include "core/model/structure.h"
#include "core/render/coordinates.h"
#include "core/render/inverse.h"
#include "core/render/rational_map.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace artcam {
namespace {

ImageF halve(const ImageF& in) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2, c = in.channels;
  ImageF out(w, h, c, in.alpha_channel);
  for (int y = 0; y < h; ++y) {
    const int y0 = 2 * y, y1 = std::min(2 * y + 1, in.height - 1);
    for (int x = 0; x < w; ++x) {
      const int x0 = 2 * x, x1 = std::min(2 * x + 1, in.width - 1);
      const float* a = in.pixel(x0, y0);
      const float* b = in.pixel(x1, y0);
      const float* d = in.pixel(x0, y1);
      const float* e = in.pixel(x1, y1);
      float* o = out.pixel(x, y);
      for (int k = 0; k < c; ++k) o[k] = 0.25f * (a[k] + b[k] + d[k] + e[k]);
    }
  }
  return out;
}

// One row of a 2×2 box level; C > 0 fixes the channel count at compile time (the RGBA8
// previews), so the inner loop unrolls and vectorises. Columns with both sources inside go
// first, without a bounds test; an odd last column repeats.
template <int C>
void halveRow(const std::uint8_t* r0, const std::uint8_t* r1, std::uint8_t* o, int in_width,
              int w, int channels) {
  const int c = C > 0 ? C : channels;
  const int whole = in_width / 2;
  for (int x = 0; x < whole; ++x) {
    const std::uint8_t* a = r0 + 2 * x * c;
    const std::uint8_t* b = r1 + 2 * x * c;
    for (int k = 0; k < c; ++k)
      o[x * c + k] = static_cast<std::uint8_t>((a[k] + a[k + c] + b[k] + b[k + c] + 2) >> 2);
  }
  for (int x = whole; x < w; ++x) {
    const int x0 = 2 * x * c;
    for (int k = 0; k < c; ++k)
      o[x * c + k] = static_cast<std::uint8_t>((2 * r0[x0 + k] + 2 * r1[x0 + k] + 2) >> 2);
  }
}

// One 2×2 box level of 8-bit samples, rounded to nearest; the last row/column repeats.
ConstImageView halveBytes(const ConstImageView& in, PixelBuffer& storage) {
  const int w = (in.width + 1) / 2, h = (in.height + 1) / 2, c = in.channels;
  // Every byte is written below.
  storage = PixelBuffer(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(c),
                        PixelBuffer::Init::Uninitialised);
  const ConstImageView out = packedView<const void>(storage.data(), w, h, c, PixelType::UInt8, in.alpha_channel);
  for (int y = 0; y < h; ++y) {
    const auto* r0 = static_cast<const std::uint8_t*>(in.row(2 * y));
    const auto* r1 = static_cast<const std::uint8_t*>(in.row(std::min(2 * y + 1, in.height - 1)));
    std::uint8_t* o = storage.data() + static_cast<size_t>(y) * static_cast<size_t>(w) * static_cast<size_t>(c);
    if (c == 4)
      halveRow<4>(r0, r1, o, in.width, w, c);
    else
      halveRow<0>(r0, r1, o, in.width, w, c);
  }
  return out;
}

// The footprint of one output pixel at the target centre, in source pixels: the shorter side
// of J⁻¹ there (J = d target / d source at the preimage, eq 2), from one Newton solve.
double centreFootprint(const Camera& camera, FrameSize source_px, FrameSize out_px) {
  try {
    const RationalMap forward(camera, source_px, out_px);
    const NewtonInverse inverse(forward, source_px, 1e-3);
    Eigen::Vector2d s;
    if (!inverse.solveFromCentre(Eigen::Vector2d(out_px.width / 2.0, out_px.height / 2.0), s, 30)) return 1.0;
    Eigen::Vector2d t;
    Eigen::Matrix2d j;
    if (!forward.evaluate(s, t, &j) || !(std::abs(j.determinant()) > 0.0)) return 1.0;
    const Eigen::Matrix2d inv = j.inverse();
    return std::min(inv.col(0).norm(), inv.col(1).norm());
  } catch (const std::invalid_argument&) {
    return 1.0;  // warpImage reports what is wrong with the camera
  }
}

}  // namespace

StoredMipPyramid::StoredMipPyramid(const ConstImageView& base, int min_size) {
  if (base.empty() || base.type != PixelType::UInt8)
    throw std::invalid_argument("an 8-bit mip pyramid needs a non-empty 8-bit image");
  views_.push_back(base);
  owned_.reserve(32);
  while (std::max(views_.back().width, views_.back().height) / 2 >= std::max(1, min_size)) {
    owned_.emplace_back();
    views_.push_back(halveBytes(views_.back(), owned_.back()));
  }
}

int StoredMipPyramid::levelFor(double footprint) const {
  if (!(footprint > 1.0)) return 0;
  const int k = static_cast<int>(std::floor(std::log2(footprint) + 1e-9));
  return std::clamp(k, 0, levels() - 1);
}

namespace {

// The level matching `scale_camera`'s footprint at the target centre, the preview's certify
// tolerance, then `warp` on that level; the note names the level.
template <class Warp>
void previewThrough(const StoredMipPyramid& pyramid, const Camera& scale_camera, const ImageView& out,
                    const WarpOptions& options, WarpSummary* summary, Warp warp) {
  const ConstImageView& base = pyramid.level(0);
  const double footprint = centreFootprint(scale_camera, {base.width, base.height}, {out.width, out.height});
  const int level = pyramid.levelFor(footprint);
  WarpOptions o = options;
  o.coordinates.certify_tolerance_px = std::max(o.coordinates.certify_tolerance_px, kPreviewCertifyTolerancePx);
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  warp(pyramid.level(level), o, report);
  report.note = "mip level " + std::to_string(level) + (report.note.empty() ? "" : "; " + report.note);
}

}  // namespace

void warpPreview(const StoredMipPyramid& pyramid, const Camera& camera, const ImageView& out,
                 const WarpOptions& options, WarpSummary* summary) {
  camera.validate();
  previewThrough(pyramid, camera, out, options, summary,
                 [&](const ConstImageView& level, const WarpOptions& o, WarpSummary& report) {
                   warpImage(level, camera, out, o, &report);
                 });
}

void warpPreview(const StoredMipPyramid& pyramid, const std::vector<Camera>& channel_cameras,
                 const ImageView& out, const WarpOptions& options, WarpSummary* summary) {
  if (channel_cameras.empty()) throw std::invalid_argument("warpPreview: no channel cameras");
  previewThrough(pyramid, channel_cameras.front(), out, options, summary,
                 [&](const ConstImageView& level, const WarpOptions& o, WarpSummary& report) {
                   warpChannels(level, channel_cameras, out, o, &report);
                 });
}

MipPyramid::MipPyramid(ImageF base, int min_size) {
  if (base.empty()) throw std::invalid_argument("a mip pyramid needs a non-empty image");
  levels_.push_back(std::move(base));
  while (std::max(levels_.back().width, levels_.back().height) / 2 >= std::max(1, min_size))
    levels_.push_back(halve(levels_.back()));
}

int MipPyramid::levelFor(double footprint) const {
  if (!(footprint > 1.0)) return 0;
  const int k = static_cast<int>(std::floor(std::log2(footprint) + 1e-9));
  return std::clamp(k, 0, levels() - 1);
}

ImageF warpPreview(const MipPyramid& pyramid, const Camera& camera, const WarpOptions& options,
                   WarpSummary* summary) {
  const ImageF& base = pyramid.level(0);
  camera.validate();
  // The output size the warp will use, to measure the footprint at the target centre.
  FrameSize out_px = camera.targetSize();
  if (options.width > 0 && options.height > 0) out_px = {options.width, options.height};
  else if (options.width > 0 || options.height > 0) {
    const double aspect = static_cast<double>(out_px.height) / out_px.width;
    out_px = options.width > 0
                 ? FrameSize{options.width, std::max(1, static_cast<int>(std::lround(options.width * aspect)))}
                 : FrameSize{std::max(1, static_cast<int>(std::lround(options.height / aspect))), options.height};
  }
  int level = 0;
  const FrameSize source_px{base.width, base.height};
  const CameraStructure structure = analyseStructure(camera);
  if (out_px.isImage() && !structure.degenerate && !structure.geometry_depends_on_attributes) {
    const auto reference = makeReferenceInverse(camera, structure, source_px, out_px);
    // Three points a pixel apart at the target centre give the footprint's two sides. The
    // reference inverse solves whole rows from x = 0, so read cx + 2 pixels of two rows.
    const int cx = out_px.width / 2, cy = out_px.height / 2;
    std::vector<Eigen::Vector2d> top(static_cast<size_t>(cx + 2)), below(top.size());
    std::vector<unsigned char> top_ok(top.size()), below_ok(top.size());
    reference->row(cy, cx + 2, top.data(), top_ok.data());
    reference->row(std::min(cy + 1, out_px.height - 1), cx + 2, below.data(), below_ok.data());
    const size_t c = static_cast<size_t>(cx);
    const Eigen::Vector2d s[3] = {top[c], top[c + 1], below[c]};
    const bool ok[3] = {top_ok[c] != 0, top_ok[c + 1] != 0, below_ok[c] != 0};
    if (ok[0] && ok[1] && ok[2]) {
      const double footprint = std::min((s[1] - s[0]).norm(), (s[2] - s[0]).norm());
      level = pyramid.levelFor(footprint);
    }
  }
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  ImageF out = warpImage(pyramid.level(level), camera, options, &report);
  report.note = "mip level " + std::to_string(level) + (report.note.empty() ? "" : "; " + report.note);
  return out;
}

}  // namespace artcam
