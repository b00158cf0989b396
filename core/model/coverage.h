// SPDX-License-Identifier: Apache-2.0
// What of the source frame an image camera maps somewhere: checked on read (validateArtcam)
// so a camera that renders nothing is refused with its reason instead of warping every photo
// to a fully transparent image, and one that loses part of the frame is reported.
//
// The position map is sampled on a 49×49 lattice of the source rectangle (coarser for chains of
// hundreds of stages, down to 5×5; in the normalised frames of frames.h); a rectangle smaller
// than the frame (a patch) on a lattice as dense, at least 5×5. A lattice cell "covers" when its four
// mapped corners are finite, span an area (not a line or a point: the shoelace area exceeds
// 1e-12 of the target frame's), and one of them lands inside the target frame. A camera with
// no covering cell renders nothing. That is refused only when nothing maps onto an area at all
// (its pole across the whole rectangle, no finite position, everything onto a line or a point):
// such a camera is broken everywhere. One that maps onto an area, all of it outside the target
// frame, is a valid camera whose pictures in these frames are empty (a patch of a fisheye's
// correction that maps beyond the frame, exact matches far from a frame the CLI can give): a
// warning, never a refusal (docs/architecture.md). A sign change of the position block's homogeneous
// weight between lattice points is a pole inside the rectangle (exact pole checks are the
// fit's, core/fit/poles.h; this one only has to see a pole that takes a visible share).
//
// Skipped for cameras that are not 2D image cameras, and for those whose position depends on
// colour or depth (which sample values would be made up here).
#pragma once

#include "core/model/camera.h"
#include "core/model/status.h"
#include "core/model/structure.h"

#include <Eigen/Core>

#include <string>

namespace artcam {

struct Coverage {
  bool checked = false;   // false: the camera is not one the check applies to
  int cells = 0;          // lattice cells sampled
  int covering = 0;       // cells that map onto an area inside the target frame
  int non_finite = 0;     // cells with a corner that maps to no finite point
  int flat = 0;           // finite cells mapped onto a line or a point
  int across_pole = 0;    // cells whose corners' weights differ in sign
  Eigen::Vector2d pole_pixel = Eigen::Vector2d::Zero();  // a source pixel next to the pole

  // Failure when nothing maps onto an area, naming the cause: the pole across the whole
  // rectangle, no finite position, everything onto a line or a point.
  Status status() const;
  // Valid, but every cell that maps onto an area lands outside the target frame.
  bool missesTarget() const;
  // Non-empty when the camera renders nothing inside the target frame (missesTarget), or when
  // part of the rectangle is lost to a pole: where, and what share.
  std::string warning() const;
};

// Over the source rectangle [x0, x1] × [y0, y1] in pixels.
Coverage measureCoverage(const Camera& camera, const Eigen::Vector2d& lo_px,
                         const Eigen::Vector2d& hi_px);
// Over the whole source frame.
Coverage measureCoverage(const Camera& camera);
// The same two for a camera whose structure the caller has analysed (structure.h).
Coverage measureCoverage(const Camera& camera, const CameraStructure& structure,
                         const Eigen::Vector2d& lo_px, const Eigen::Vector2d& hi_px);
Coverage measureCoverage(const Camera& camera, const CameraStructure& structure);

}  // namespace artcam
