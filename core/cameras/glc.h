// SPDX-License-Identifier: Apache-2.0
// General linear cameras [YM04] as object-space ARTcams.
//
// A GLC is fixed by three generator rays, each given in two-plane form: it crosses the plane
// z = 0 at `st` and z = 1 at `uv` (camera coordinates, camera_pose.h). Its rays are the affine
// combinations Σ wᵢ rᵢ (Σ wᵢ = 1) of the generators, and the ray with weights w shows at the
// image point Σ wᵢ imageᵢ. Pinhole, orthographic, push-broom, crossed-slits and the "twisted"
// bilinear cameras are all GLCs.
//
// Projection is rational quadratic, which is why the GLC is an RTcam: at depth ζ = Z/W the
// generators cross at gᵢ(ζ) = stᵢ + ζ(uvᵢ - stᵢ), and P = (X, Y) is their affine combination
// with barycentric weights wᵢ = Nᵢ/D, where (with p = (X, Y) and gᵢ scaled by W)
//   D  = cross(g₂ - g₁, g₃ - g₁),   N₁ = cross(g₂ - p, g₃ - p), N₂ = cross(g₃ - p, g₁ - p),
//   N₃ = cross(g₁ - p, g₂ - p)
// are quadratic forms of (X, Y, Z, W). Outputs (u, v) = Σ Nᵢ imageᵢ / D.
// Nearness (projective_cameras.h), with D's sign chosen positive far away: D vanishes at the
// depths of the foci; with real roots ρ' ≤ ρ it is (Z - ρW)W/D = 1/(|d₂|(Z - ρ')), falling along
// the rays and positive beyond the nearer focus (in front of a pinhole GLC); with one root or
// complex roots W²/D; for parallel generators (orthographic GLCs, D constant) 1 - Z/far.
#pragma once

#include "core/cameras/camera_pose.h"
#include "core/model/camera.h"

#include <Eigen/Core>

#include <array>

namespace artcam {

struct GeneratorRay {
  Eigen::Vector2d st;     // crossing of z = 0
  Eigen::Vector2d uv;     // crossing of z = 1
  Eigen::Vector2d image;  // where the ray shows in the image (normalised frame)
};

struct GlcParams {
  std::array<GeneratorRay, 3> rays;
  double far = 1e6;  // orthographic GLCs only
  CameraPose pose;
};

// Three generators whose image points are `focal`·uvᵢ: for a pinhole GLC (all stᵢ = 0) the
// image is then exactly the pinhole's.
GlcParams glcFromTwoPlanes(const std::array<Eigen::Vector4d, 3>& s_t_u_v, double focal);

// Throws std::invalid_argument when the image points are collinear or the generators are
// degenerate (D ≡ 0: the three rays lie in one plane).
Camera glcCamera(const GlcParams& p);
Ray glcRay(const GlcParams& p, const Eigen::Vector2d& image);

}  // namespace artcam
