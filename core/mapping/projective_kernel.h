// SPDX-License-Identifier: Apache-2.0
// The coordinate kernel of a projective camera (identity, translation, affine, homography), for
// makeCoordinateKernel (coordinates.h): the inverse homography in closed form, span by span,
// in double, or in float lanes where positions stay within 1e-3 px of the double result.
#pragma once

#include "core/mapping/coordinates.h"
#include "core/model/frames.h"

#include <Eigen/Core>

#include <memory>

namespace artcam {

// target_from_source in pixels (column form); throws std::invalid_argument when it is singular.
std::unique_ptr<CoordinateKernel> makeProjectiveKernel(const Eigen::Matrix3d& target_from_source,
                                                       FrameSize source_px, bool scalar_only);

}  // namespace artcam
