// SPDX-License-Identifier: Apache-2.0
// The bundled stereo sample (`artcam sample stereo-house`): a gabled house on a lawn, ray traced
// in code from two pinholes a baseline apart (a rectified pair: one orientation, the right eye
// along the left's x axis), with the left view's true depth — the truth the stereo matcher
// (stereo_depth.h) is checked against, and the scene of the paper's Fig 2 (its walls seen
// obliquely, unfolded from the stereo depth).
//
// Surfaces carry procedural texture (bricks, tiles, grass: hashed value noise in the surface's
// own coordinates), so the matcher has detail at every scale; the sky has none, and no depth.
#pragma once

#include "core/model/image.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace artcam {

struct StereoHouseScene {
  int width = 640, height = 480;
  double focal_px = 560.0;
  double baseline = 0.25;  // world units (the house is 4 wide, 3 deep, 3.2 to the ridge)
  Eigen::Vector3d left_eye{5.2, 1.7, 7.4};
  Eigen::Vector3d look_at{0.0, 1.3, 0.0};
  int supersample = 2;  // per axis, for the colour; depth is the pixel centre's

  // The camera's axes (world): right, down and forward; pixel (x, y) looks along
  // forward + (x + 0.5 − w/2)/f · right + (y + 0.5 − h/2)/f · down.
  Eigen::Vector3d right() const;
  Eigen::Vector3d down() const;
  Eigen::Vector3d forward() const;
  double baselineFocal() const { return baseline * focal_px; }
};

// A planar wall of the house and its outline in the left view.
struct HouseWall {
  std::string name;                      // "front", "side", …
  std::vector<Eigen::Vector3d> corners;  // world, in order around the wall
  std::vector<Eigen::Vector2d> left_px;  // the corners projected into the left view
};

struct StereoHousePair {
  ImageF left, right;            // linear RGB
  ImageF left_depth;             // 1 channel: depth along the view axis; 0 for the sky
  std::vector<HouseWall> walls;  // the walls the left view sees (front, side)
};

StereoHousePair renderStereoHouse(const StereoHouseScene& scene = {});

// The colour (linear RGB) the scene shows along one ray: what an orthographic view of a wall
// sees, for checking an unfolded picture (unfold_walls.h) against the scene itself.
Eigen::Vector3d stereoHouseColourAlong(const Eigen::Vector3d& origin,
                                       const Eigen::Vector3d& direction);

}  // namespace artcam
