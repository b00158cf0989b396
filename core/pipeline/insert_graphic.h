// SPDX-License-Identifier: Apache-2.0
// Inserting a graphic into a photo of a scene with a curved reflector or refractor (the paper's
// §5, Figs 7 and 8): one entry point for `artcam insert` and the studio's Insertion mode, so the
// command and the preview composite alike.
//
// Frames: the graphic stands for the calibration board's canonical view (board PIXELS, the
// cameras' source frame, the graphic stretched to it); the cameras' target frame is the full
// photo in PIXELS (centres at i + 0.5), and so is the region. The photo handed in may be a
// smaller copy (a preview): cameras and region are scaled to it. Colours are linear and
// premultiplied.
//
// Decisions:
// - Fig 7(c) puts the graphic in both places: on the plane it lies on, seen directly (the
//   board → photo homography of Fig 7b, fitted from board points clicked on the table), and in
//   the object, through the piecewise camera fitted to the grid's reflection. The plane's copy
//   goes under, the object's over.
// - The region is the object's outline. Inside it the object hides the plane, so the plane's
//   copy is cut away there; outside it nothing is reflected, so the object's copy is cut away.
//   Without a region both copies are drawn wherever their cameras reach.
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/piecewise_camera.h"
#include "core/pipeline/render.h"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace artcam {

struct InsertionCameras {
  PiecewiseCamera object;               // board → photo through the reflector or refractor
  std::optional<Camera> plane;          // board → photo seen directly (a homography); none: skip
  std::vector<Eigen::Vector2d> region;  // the object's outline, photo pixels; < 3 points: none
};

struct InsertSummary {
  RenderSummary object;
  RenderSummary plane;  // path Geometry and size 0×0 when there is no plane camera
  double ms = 0.0;      // both renders and the composites
};

// Fig 7b: the board → photo homography from board points the photo sees directly (board pixels
// → photo pixels, at least 4, e.g. the board's corners clicked on the table): the conditioned
// DLT of fit_image.h, refined. Collinear or coincident clicks are refused with the fit's reason.
FitSummary fitBoardHomography(const std::vector<PointMatch>& board_to_photo, FrameSize board,
                              FrameSize photo);
// Its inverse, photo → board, fitted to the same matches swapped: it takes a grid photographed
// on the table to the canonical view (Fig 7b). The table's horizon may cross the photo, so a
// pole in the photo frame is allowed; points beyond the horizon map nowhere.
FitSummary fitBoardFromPhoto(const std::vector<PointMatch>& board_to_photo, FrameSize board,
                             FrameSize photo);

// The photo with the graphic composited where the cameras put it. `options.warp`'s size is
// ignored (the photo's size is the output's). Throws std::invalid_argument for cameras whose
// frames disagree (the plane's target frame must be the object camera's) or an empty photo.
ImageF insertGraphic(const ImageF& photo, const ImageF& graphic, const InsertionCameras& cameras,
                     const RenderOptions& options = {}, InsertSummary* summary = nullptr);

}  // namespace artcam
