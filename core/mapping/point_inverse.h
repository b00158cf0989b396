// SPDX-License-Identifier: Apache-2.0
// The preimage of single target points through a camera's position map: where a point of the
// warped result came from in the source. The studio maps a click on its result back to the
// photo through it (a pair's source, a depth stroke), so what is placed is the photo pixel the
// result shows there.
//
// The rule is the gather warp's own (inverse.h): a preimage lies on the source centre's side of
// every pole curve and in its fold; a central map (radial lenses, twists: central_inverse.h)
// takes its closed form, any other map damped Newton on eq 1 from, in order, the caller's start,
// the target point read as a source point (the frames coincide for studio cameras, so a mild
// warp's preimage is near), and the map linearised at the source centre. Whether the preimage
// lies inside the source image is the caller's question (position_map.h's rule for the warp).
//
// Conventions: pixel frames on both sides, centres at i + 0.5 (frames.h). Only the position
// block is read (rational_map.h): callers check that positions read position alone
// (CameraStructure::geometry_depends_on_attributes) and refuse otherwise.
#pragma once

#include "core/mapping/central_inverse.h"
#include "core/mapping/inverse.h"
#include "core/mapping/rational_map.h"

#include <Eigen/Core>

#include <optional>

namespace artcam {

class PointInverse {
 public:
  // Throws std::invalid_argument without a 2D position block, or when the map is undefined all
  // around the source centre.
  PointInverse(const Camera& camera, FrameSize source_px, FrameSize target_px);

  // The source point (source pixels) that maps to `target` (target pixels); empty where there is
  // none. `start`: a guess tried first (the last solution of a drag, say).
  std::optional<Eigen::Vector2d> sourceOf(
      const Eigen::Vector2d& target,
      const std::optional<Eigen::Vector2d>& start = std::nullopt) const;

  // The forward map at a source point (target pixels); empty on a pole curve.
  std::optional<Eigen::Vector2d> targetOf(const Eigen::Vector2d& source) const;

 private:
  FrameSize source_px_, target_px_;
  NewtonInverse newton_;
  std::optional<CentralInverse> central_;
};

}  // namespace artcam
