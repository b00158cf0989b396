// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the test executables: seeded randomness, fixtures made in code.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <random>
#include <string>

namespace artcam::test {

// A fixed-seed generator so every run sees the same "random" data.
std::mt19937_64& rng();
double uniform(double lo, double hi);

// A well-conditioned random rational camera on a w×h image: identity plus small quadratic terms.
Camera randomRationalCamera(FrameSize source, FrameSize target, double strength = 0.05);
// A random homography camera (tensors lifted with l at infinity), mild perspective.
Camera randomHomographyCamera(FrameSize source, FrameSize target);

// Path of a file in resources/.
std::string resourcePath(const std::string& name);

}  // namespace artcam::test
