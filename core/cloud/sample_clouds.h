// SPDX-License-Identifier: Apache-2.0
// Clouds made by the project: the sample of the paper's Fig 1 (a coloured 3×3×3 cube of cubes,
// written to resources/cube.ply by `artcam preset cube-cloud`) and test fixtures.
#pragma once

#include "core/cloud/point_cloud.h"

namespace artcam {

struct CubeOfCubesOptions {
  int samples_per_edge = 10;  // points along each edge of a small cube's face (n² per face)
  double half_size = 1.0;     // the big cube spans [-half_size, half_size]³
  double gap = 0.12;          // fraction of each cell left empty between small cubes
};

// 27 small cubes, surfaces only (27·6·n² points). Cube (i, j, k) ∈ {0, 1, 2}³ along (x, y, z) has
// the sRGB colour (0.15 + 0.425·i, 0.15 + 0.425·j, 0.15 + 0.425·k), stored linear:
// red grows along x, green along y (up), blue along z, so warm and cold cubes sit at opposite
// corners and every cube has all three channels (the layers of chromatic aberration show).
PointCloud cubeOfCubes(const CubeOfCubesOptions& options = {});

// The colour of small cube (i, j, k), linear premultiplied (alpha 1).
Eigen::Vector4f cubeOfCubesColour(int i, int j, int k);

}  // namespace artcam
