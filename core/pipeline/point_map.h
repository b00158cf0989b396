// SPDX-License-Identifier: Apache-2.0
// Source pixels → target pixels through any camera value, as `artcam map` and the Python
// module's Camera.map answer: a piecewise camera through the patch that holds the point (as
// the render does), a layered camera once per layer, a camera with colour or depth blocks
// through its position part where positions read position alone (eq 4), refused otherwise.
#pragma once

#include "core/model/artcam.h"
#include "core/model/status.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace artcam {

class PointMapper {
 public:
  // Fails (one line starting with `name`) for a 3D camera, one without a position block, or one
  // whose positions depend on colour or depth (where a point goes then depends on the photo).
  static Result<PointMapper> of(const Artcam& camera, const std::string& name);

  size_t layers() const { return geometry_.size(); }
  // The target pixel of `source_px` through layer `layer`; none on a pole curve, or outside
  // every patch of a piecewise camera (where the render leaves the pixel empty).
  std::optional<Eigen::Vector2d> map(size_t layer, const Eigen::Vector2d& source_px) const;

 private:
  std::vector<Camera> geometry_;
  std::optional<PiecewiseCamera> pieces_;
};

}  // namespace artcam
