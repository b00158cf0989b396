// SPDX-License-Identifier: Apache-2.0
#include "core/render/preview.h"

#include "core/model/analysed_cameras.h"
#include "core/mapping/coordinates.h"
#include "core/mapping/inverse.h"
#include "core/mapping/rational_map.h"
#include "core/model/structure.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace artcam {

namespace {

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
  const CameraStructure structure = validatedStructure(camera);
  warpPreview(pyramid, AnalysedCamera{camera, structure}, out, options, summary);
}

void warpPreview(const StoredMipPyramid& pyramid, const AnalysedCamera& camera, const ImageView& out,
                 const WarpOptions& options, WarpSummary* summary) {
  camera.camera.validate();
  previewThrough(pyramid, camera.camera, out, options, summary,
                 [&](const ConstImageView& level, const WarpOptions& o, WarpSummary& report) {
                   warpImage(level, camera, out, o, &report);
                 });
}

void warpPreview(const StoredMipPyramid& pyramid, const std::vector<Camera>& channel_cameras,
                 const ImageView& out, const WarpOptions& options, WarpSummary* summary) {
  const AnalysedCameras analysed(channel_cameras);
  warpPreview(pyramid, analysed.cameras(), out, options, summary);
}

void warpPreview(const StoredMipPyramid& pyramid, const std::vector<AnalysedCamera>& channel_cameras,
                 const ImageView& out, const WarpOptions& options, WarpSummary* summary) {
  if (channel_cameras.empty()) throw std::invalid_argument("warpPreview: no channel cameras");
  previewThrough(pyramid, channel_cameras.front().camera, out, options, summary,
                 [&](const ConstImageView& level, const WarpOptions& o, WarpSummary& report) {
                   warpChannels(level, channel_cameras, out, o, &report);
                 });
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
