// SPDX-License-Identifier: Apache-2.0
// The cameras `artcam bench render` times by default besides its kernel rows: the cameras users
// make, not only the one the kernel handles best. Made in code for any frame size:
//   homography                  the projective kernel's time, the yardstick of the targets
//   lens-compact, lens-wide,    quadratic fits of radial lens models (lensfun's poly5
//   fisheye                     a(r) = r (1 + k1 r² + k2 r⁴) with a compact zoom's and a wide
//                               angle's coefficients; an equisolid fisheye to rectilinear) to
//                               matches sampled over the frame, the way `artcam fit` makes them
//   every image preset          barrel, pincushion, twist, inverse-perspective and
//                               chromatic-aberration at their defaults and at a strong setting
//                               (barrel k = -0.6 leaves the corners without any preimage)
//   piecewise                   the fisheye as a piecewise camera (`fit --piecewise`)
// `--cameras FILE…` replaces the suite by .artcam files (e.g. lensfun lenses).
#pragma once

#include "core/model/artcam.h"
#include "core/model/frames.h"

#include <string>
#include <vector>

namespace artcam::cli {

struct SuiteCamera {
  std::string name;
  Artcam camera;
};

std::vector<SuiteCamera> benchCameraSuite(FrameSize size);

}  // namespace artcam::cli
