// SPDX-License-Identifier: Apache-2.0
// The straight-line tests' own truths, independent of core/fit/fit_lines: a radial lens with a
// closed-form inverse, and a straightness measure of their own.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace artcam::test {

// The photo point (normalised frame) of a scene point seen through the centred radial lens
// u = U / (1 - k |U|²) (photo → scene), which one quadratic camera represents exactly:
// |U| = r / (1 - k r²) solved for r in closed form.
Eigen::Vector2d radialPhotoFromScene(double k, const Eigen::Vector2d& scene);

// Largest distance of the points from their total-least-squares line (pixels in, pixels out).
double bowOf(const std::vector<Eigen::Vector2d>& points);

}  // namespace artcam::test
