// SPDX-License-Identifier: Apache-2.0
// The canvas's result mapped back to the photo: the preimage of a result pixel through the
// camera the result shows (the document's whole camera, effects included: a feature seen on the
// result came from there in the photo), so pairs' sources and depth strokes can be placed where
// the user looks, as in Puppet Warp and Liquify. Frames: the result is drawn in the photo's frame
// (canvas.h), so result and photo pixels are both of the photo's size.
//
// One inverse per camera, made on demand (Canvas::resultInverse) and shared: a drag keeps the one
// it began with, so a source dragged on the result follows the cursor mapped through the camera
// as it was, not through the camera its own moves refit (no feedback).
//
// Refused, with a message naming what to do instead: a result point with no preimage (beyond the
// camera's pole or fold: core/mapping/point_inverse.h), one whose preimage lies outside the photo
// (the result is transparent there), and cameras that are not inverted point by point (a
// piecewise camera; positions that read colour or depth, eq 8/9).
#pragma once

#include "core/mapping/point_inverse.h"
#include "core/model/camera.h"

#include <QString>

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace artcam {
struct Artcam;
}

namespace artcam::ui {

struct PhotoPoint {
  std::optional<Eigen::Vector2d> pixel;  // photo pixels
  QString refusal;                       // why there is none: a status-bar line
};

class ResultInverse {
 public:
  // The inverse of `camera`'s first layer, result and photo both `photo_px`.
  ResultInverse(const Artcam& camera, FrameSize photo_px);

  // The photo pixel the result shows at `result_px` (result pixels); `start` a guess in photo
  // pixels (a drag's last answer).
  PhotoPoint photoPixelOf(const Eigen::Vector2d& result_px,
                          const std::optional<Eigen::Vector2d>& start = std::nullopt) const;
  // Where a photo pixel shows on the result; empty on the pole, or when refused.
  std::optional<Eigen::Vector2d> resultPixelOf(const Eigen::Vector2d& photo_px) const;

  // For each pixel centre of a `grid`-sized raster over the result, the photo pixel it shows
  // (NaN where none), from the warp's inverse map: the depth tint's lookup, made once per camera
  // and size and kept.
  const std::vector<Eigen::Vector2f>& photoPixelsOfGrid(FrameSize grid) const;

 private:
  FrameSize photo_px_;
  std::optional<PointInverse> inverse_;
  Camera camera_;    // the first layer, for the grid
  QString refusal_;  // set when the camera is refused
  mutable FrameSize grid_px_{0, 0};
  mutable std::vector<Eigen::Vector2f> grid_;
};

}  // namespace artcam::ui
