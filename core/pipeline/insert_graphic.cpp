// SPDX-License-Identifier: Apache-2.0
// Graphic insertion into reflections and onto their plane; see insert_graphic.h.
#include "core/pipeline/insert_graphic.h"

#include "core/depth/region_mask.h"
#include "core/model/artcam.h"
#include "core/piecewise/piecewise_render.h"

#include <chrono>
#include <utility>
#include <stdexcept>

namespace artcam {
namespace {

// Clears (to transparent) the pixels of `image` whose mask coverage is `clear_where_inside`.
void cutAway(ImageF& image, const RegionMask& mask, bool clear_where_inside) {
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if ((mask.at(x, y) != 0) == clear_where_inside) {
        float* p = image.pixel(x, y);
        for (int c = 0; c < image.channels; ++c) p[c] = 0.0f;
      }
}

}  // namespace

FitSummary fitBoardHomography(const std::vector<PointMatch>& board_to_photo, FrameSize board,
                              FrameSize photo) {
  FitOptions options;
  options.model = ModelClass::Homography;
  options.diagnostics = false;  // no model choice to justify
  return fitImageCamera(board_to_photo, board, photo, options);
}

FitSummary fitBoardFromPhoto(const std::vector<PointMatch>& board_to_photo, FrameSize board,
                             FrameSize photo) {
  std::vector<PointMatch> swapped = board_to_photo;
  for (PointMatch& m : swapped) std::swap(m.source, m.target);
  FitOptions options;
  options.model = ModelClass::Homography;
  options.diagnostics = false;
  options.require_pole_free = false;
  return fitImageCamera(swapped, photo, board, options);
}

ImageF insertGraphic(const ImageF& photo, const ImageF& graphic, const InsertionCameras& cameras,
                     const RenderOptions& options, InsertSummary* summary) {
  if (photo.empty() || graphic.empty())
    throw std::invalid_argument("insertGraphic: empty photo or graphic");
  if (cameras.object.patches.empty())
    throw std::invalid_argument("insertGraphic: the object camera has no patches");
  const FrameSize target = cameras.object.target_size;
  if (cameras.plane && cameras.plane->targetSize() != target)
    throw std::invalid_argument("insertGraphic: the plane camera's target frame is not the photo's");
  const auto start = std::chrono::steady_clock::now();

  RenderOptions sized = options;
  sized.warp.width = photo.width;
  sized.warp.height = photo.height;

  RegionMask mask;
  if (cameras.region.size() >= 3) {
    // The region is in full-frame photo pixels; a preview photo is a scaled copy.
    const double sx = double(photo.width) / target.width;
    const double sy = double(photo.height) / target.height;
    std::vector<Eigen::Vector2d> scaled;
    scaled.reserve(cameras.region.size());
    for (const Eigen::Vector2d& p : cameras.region) scaled.emplace_back(p.x() * sx, p.y() * sy);
    mask = RegionMask(photo.width, photo.height);
    mask.fillPolygon(scaled);
  }

  ImageF out = photo;
  InsertSummary local;
  if (cameras.plane) {
    ImageF on_plane = render(RenderInputs::of(graphic), Artcam(*cameras.plane), sized, &local.plane);
    if (!mask.empty()) cutAway(on_plane, mask, true);
    compositeOver(on_plane, out);
  }
  Artcam lens(cameras.object.patches.front().camera);
  lens.pieces = cameras.object;
  ImageF in_object = render(RenderInputs::of(graphic), lens, sized, &local.object);
  if (!mask.empty()) cutAway(in_object, mask, false);
  compositeOver(in_object, out);

  local.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (summary) *summary = local;
  return out;
}

}  // namespace artcam
