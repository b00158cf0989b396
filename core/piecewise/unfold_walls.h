// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 2: a building's walls "unfolded" into one picture, each wall seen
// orthogonally, from one image of a stereo pair and the depth it gives (stereo_depth.h). The
// user marks each wall's outline; the wall's plane comes from the depth inside it (a robust
// least-squares plane), each wall maps to its own rectangle of the output by the homography
// photo → plane → wall coordinates (a position-only camera, eq 3 with Q = lifted linear maps),
// and the walls lie side by side, bottom-aligned, at one scale: a piecewise camera (§5) whose
// patches are the walls. A wall shorter than the tallest has a band above it in the picture; the
// roof seen over the wall's top edge (up to where the depth ends: the sky) is stretched to fill
// it, as the paper's Fig 2 does.
#pragma once

#include "core/model/artcam.h"
#include "core/model/image.h"
#include "core/model/status.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

// A wall's outline in the photo, in order around the wall, its FIRST edge the wall's base (it
// gives the wall's horizontal: bottom-left → bottom-right); the walls left to right.
// A wall marked on the photo (core/io/walls_csv.h reads them from a file).
struct WallOutline {
  std::string name;
  std::vector<Eigen::Vector2d> photo_px;
};

// Whether a photo point lies inside the outline (even-odd rule).
bool insideOutline(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& p);

struct UnfoldOptions {
  double focal_px = 0.0;  // the photo's focal length in pixels (required)
  // The principal point; negative: the photo's centre.
  Eigen::Vector2d principal_px{-1.0, -1.0};
  // Output pixels per depth unit along the walls; 0: the walls span the photo's width.
  double px_per_unit = 0.0;
  // The picture's frame; empty: the walls' own extent at px_per_unit. Given (the studio: the
  // photo's frame, which its camera keeps), the walls are laid out at the largest scale that
  // fits it, from its top-left corner (the same picture, then transparent to the frame's other
  // sides), and px_per_unit is not used.
  FrameSize frame{0, 0};
  // Fill the band above each shorter wall with the roof seen over it (false: leave it empty).
  bool stretch_roof = true;
};

struct UnfoldedWall {
  std::string name;
  Eigen::Vector3d normal;            // the fitted plane's, in the camera's frame (x right, y down)
  double width = 0.0, height = 0.0;  // in depth units
  int depth_samples = 0;             // depth pixels inside the outline used by the plane
  double plane_rms = 0.0;            // their distance from the plane, depth units
  double left_out_share = 0.0;       // of the outline past the seam with a neighbour (not shown)
  // The roof over the wall's top edge, measured up the wall's plane to where the depth ends
  // (depth units; 0: no band, or no roof found over the wall), and the factor it is stretched by
  // to reach the picture's top.
  double roof_height = 0.0;
  double roof_stretch = 0.0;
};

struct UnfoldSummary {
  std::vector<UnfoldedWall> walls;
  FrameSize size;  // the unfolded picture
  double px_per_unit = 0.0;
};

// The unfolding camera for `photo` (the size of the image `depth` was measured for; the depth
// map may be of another size, scaled to the photo's frame). Fails, naming the wall, for an
// outline with fewer than 3 corners or outside the frame, too little depth inside it, a plane
// seen edge-on, or walls that overlap.
Result<Artcam> unfoldWalls(const ImageF& depth, FrameSize photo,
                           const std::vector<WallOutline>& walls, const UnfoldOptions& options,
                           UnfoldSummary* summary = nullptr);

}  // namespace artcam
