// SPDX-License-Identifier: Apache-2.0
// Multi-perspective pictures from one photo and its depth: push-broom, crossed-slits and general
// linear cameras (GLCs, core/cameras/glc.h) applied in image space, so a photo seen by one
// pinhole is re-seen by a camera whose rays do not meet in one point (the paper's §1: the
// RTcam subsumes GLCs, push-broom and X-slit cameras; composed with the photo's depth it is an
// ARTcam whose geometry reads depth).
//
// Conventions:
// - Image points are in the photo's NORMALISED frame (frames.h: the larger side spans [-1, 1],
//   v down); source and target frame are the photo's.
// - The photo is a pinhole of focal f (normalised units per unit of X/Z) at the origin of
//   camera coordinates (camera_pose.h: x right, y down, z forward), principal point at the
//   frame centre; a pixel (u, v) with depth d (the depth image's value, distance along z) is
//   the point P = (u·d/f, v·d/f, d).
// - The camera is over [position 3 | colour 4 | depth 2] (eq 4); colour passes unchanged, the
//   depth output is the input depth, so depth of field can follow it.
//
// Why a chain of two stages: a GLC's image point is a ratio of quadratics in (X, Y, Z, W)
// (glc.h), and P's coordinates X = u·d/f are already products of a position and a depth
// element, so the composition is of degree 4 in x and no single stage (eq 3) holds it.
// Stage 1 back-projects: position (u·d, v·d, f·w·d_h) → (X, Y, 1), depth (d·d, d·d_h) → Z;
// stage 2 is the GLC's own tensors read on (X, Y, Z, 1) = (position u, position v, depth d,
// position w) of the re-homogenised stage-1 output (eq 5). The geometry reads depth, so
// render() takes the splat path (core/render/splat.h).
//
// A pixel without depth (a hole of the depth image, d = 0) has no 3D point: stage 1 gives its
// depth the weight d·d_h, so it has no image and renders transparent (the splat drops its
// triangles). These cameras need depth over the whole photo.
//
// Parametrisations. The photo's focal cancels from each: every parameter is a depth or an
// image shift, so the presets do not ask for it (the general photoGlcCamera takes any GLC
// stated in 3D, and then the focal matters).
// - Push-broom [GH97]: orthographic along the sweep direction a = (cos θ, sin θ), perspective
//   across it (b ⟂ a), scaled to agree with the photo at the reference depth d_r:
//     a·p' = (a·p)·d/d_r,   b·p' = b·p.
//   Things nearer than d_r narrow along a, farther ones widen.
// - Crossed slits [ZFPW03]: the slit that sets u is the line {X = 0, Z = −s_u}, the one that
//   sets v is {Y = 0, Z = −s_v} (s ≥ 0: behind the photo's centre, so every depth > 0 lies
//   beyond both and there is no pole), each axis scaled to agree with the photo at d_r:
//     u' = u·d·(d_r + s_u)/(d_r·(d + s_u)),   v' = v·d·(d_r + s_v)/(d_r·(d + s_v)).
//   s = 0 keeps that axis as the photo's; s_u = s_v = 0 is the photo itself.
// - Parallax GLC: the pinhole whose centre slides with the image point: the ray of output
//   point p' has the photo's direction (p'/f, 1) and starts at −e(p')/f on the plane z = 0,
//   for the affine field e(p') = e₀ + p'_u·e_u + p'_v·e_v (image units at depth 1). Then
//     p' = p + e(p')/d,
//   a point at depth d moves by e/d: e₀ alone is a sideways step of the photo's camera
//   (parallax), e_u = (k, 0) a slit at depth k, and e_u = (0, t), e_v = (−t, 0) the twisted
//   GLC that turns a point at depth d by atan(t/d) about the centre (and shrinks it by the
//   cosine of that angle). The rays are the affine combinations of three generators, as a
//   GLC's are [YM04].
#pragma once

#include "core/cameras/glc.h"
#include "core/model/camera.h"

#include <Eigen/Core>

namespace artcam {

// The GLC `glc` (camera coordinates of the photo's pinhole, its pose included) applied to the
// photo of focal `photo_focal` with depth, over the normalised frame of `frame`. Throws
// std::invalid_argument for a focal that is not positive and finite or a degenerate GLC.
Camera photoGlcCamera(const GlcParams& glc, double photo_focal, FrameSize frame);

struct PhotoPushbroomParams {
  double reference_depth = 3.0;  // d_r: the depth whose picture keeps its size
  double angle_deg = 0.0;        // θ: the sweep direction, 0 along u (rows), 90 along v
};
GlcParams photoPushbroomGlc(const PhotoPushbroomParams& p, double photo_focal);
Camera photoPushbroomCamera(const PhotoPushbroomParams& p, FrameSize frame);

struct PhotoXSlitParams {
  double slit_u_behind = 0.0;    // s_u ≥ 0: the u slit's distance behind the photo's centre
  double slit_v_behind = 3.0;    // s_v ≥ 0: the v slit's
  double reference_depth = 3.0;  // d_r > 0
};
GlcParams photoXSlitGlc(const PhotoXSlitParams& p, double photo_focal);
Camera photoXSlitCamera(const PhotoXSlitParams& p, FrameSize frame);

struct PhotoParallaxParams {
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();  // e₀: image shift of depth 1 at the centre
  Eigen::Vector2d shift_per_u{0.0, 0.3};            // e_u: its change per unit of u
  Eigen::Vector2d shift_per_v{-0.3, 0.0};           // e_v: per unit of v
};
GlcParams photoParallaxGlc(const PhotoParallaxParams& p, double photo_focal);
Camera photoParallaxCamera(const PhotoParallaxParams& p, FrameSize frame);

}  // namespace artcam
