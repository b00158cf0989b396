// SPDX-License-Identifier: Apache-2.0
#include "core/effects/multi_perspective.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace artcam {

namespace {

// Elements of x = [u v w | r g b a | d d_h] (eq 4).
constexpr int kU = 0, kV = 1, kW = 2, kR = 3, kD = 7, kDh = 8, kN = 9;
Eigen::VectorXd e(int i) { return Eigen::VectorXd::Unit(kN, i); }

// The presets' parametrisations do not depend on the photo's focal (header), so any positive
// one gives the same camera; 1 keeps the stage-1 numbers at the scale of the depths.
constexpr double kPresetFocal = 1.0;

// The generators of a GLC whose rays vary affinely with the image point: three image points
// in general position and the rays `rayAt` gives them (a GLC's rays are the affine
// combinations of its generators, glc.h).
template <typename RayAt>
GlcParams generatorsOf(RayAt rayAt) {
  GlcParams glc;
  const Eigen::Vector2d images[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
  for (int i = 0; i < 3; ++i) {
    const auto [st, uv] = rayAt(images[i]);
    glc.rays[static_cast<size_t>(i)] = GeneratorRay{st, uv, images[i]};
  }
  return glc;
}

void requirePositive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(what) + " must be a positive number");
}

// Colour and depth unchanged (the identity z_i = x_i·w of docs/architecture.md, "The model").
void passColourAndDepth(Stage& stage) {
  for (int i = kR; i < kN; ++i) stage.q.push_back(symmetricOuter(e(i), e(kW)));
}

}  // namespace

Camera photoGlcCamera(const GlcParams& glc, double photo_focal, FrameSize frame) {
  requirePositive(photo_focal, "the photo's focal");
  if (!frame.isImage()) throw std::invalid_argument("a photo camera needs an image frame");
  // Stage 1, back-projection through the photo's pinhole: (X, Y) = (u·d, v·d)/(f·w·d_h).
  // Colour passes; depth is written (d·d, d·d_h): still d, but with a weight that vanishes where
  // there is no depth (d = 0), so such a pixel's stage-2 input is not finite and it has no
  // image. Without it the photo's centre (0, 0, 0) would be projected, and a GLC whose ray
  // passes through it (the twisted one does, at its centre) would gather every hole there.
  Stage back;
  back.q = {symmetricOuter(e(kU), e(kD)), symmetricOuter(e(kV), e(kD)),
            photo_focal * symmetricOuter(e(kW), e(kDh))};
  for (int i = kR; i < kD; ++i) back.q.push_back(symmetricOuter(e(i), e(kW)));
  back.q.push_back(symmetricOuter(e(kD), e(kD)));
  back.q.push_back(symmetricOuter(e(kD), e(kDh)));

  // Stage 2, the GLC's tensors on (X, Y, Z, W) = x·S, so Q = S Q_glc Sᵀ (frames.h's input-side
  // rule for row vectors). Its outputs (u, v, nearness, D) keep u, v over D (eq 1); the
  // nearness is dropped, the depth output is the input depth.
  const Camera object = glcCamera(glc);
  const std::vector<Eigen::MatrixXd>& q = object.stages().front().q;
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(kN, 4);
  s(kU, 0) = s(kV, 1) = s(kD, 2) = s(kW, 3) = 1.0;
  Stage project;
  project.q = {s * q[0] * s.transpose(), s * q[1] * s.transpose(), s * q[3] * s.transpose()};
  passColourAndDepth(project);

  return Camera(
      {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}, Block{BlockKind::Depth, 2}},
      {back, project}, frame, frame);
}

GlcParams photoPushbroomGlc(const PhotoPushbroomParams& p, double photo_focal) {
  requirePositive(p.reference_depth, "push-broom reference depth");
  requirePositive(photo_focal, "the photo's focal");
  if (!std::isfinite(p.angle_deg)) throw std::invalid_argument("push-broom angle must be finite");
  const double theta = p.angle_deg * std::numbers::pi / 180.0;
  const Eigen::Vector2d a(std::cos(theta), std::sin(theta)), b(-a.y(), a.x());
  const double f = photo_focal, dr = p.reference_depth;
  // The ray of p' is the set of points P with a·p' = (a·P)·f/d_r (orthographic, scale f/d_r)
  // and b·p' = f·(b·P)/Z (perspective): (X, Y) = a·(a·p')·d_r/f + b·(b·p')·Z/f.
  return generatorsOf([&](const Eigen::Vector2d& image) {
    const Eigen::Vector2d st = a * a.dot(image) * dr / f;
    return std::pair{st, Eigen::Vector2d(st + b * b.dot(image) / f)};
  });
}

GlcParams photoXSlitGlc(const PhotoXSlitParams& p, double photo_focal) {
  requirePositive(p.reference_depth, "crossed-slits reference depth");
  requirePositive(photo_focal, "the photo's focal");
  if (!(p.slit_u_behind >= 0.0) || !(p.slit_v_behind >= 0.0) || !std::isfinite(p.slit_u_behind) ||
      !std::isfinite(p.slit_v_behind))
    throw std::invalid_argument(
        "crossed slits: the slits' distances behind the photo's centre "
        "must be numbers >= 0");
  const double f = photo_focal, dr = p.reference_depth;
  // u' = k_u·f·X/(Z + s_u) with k_u = (d_r + s_u)/d_r (the photo's scale at d_r); likewise v.
  // The ray of p' crosses depth Z at X = u'·(Z + s_u)/(k_u·f), Y = v'·(Z + s_v)/(k_v·f).
  const double su = p.slit_u_behind, sv = p.slit_v_behind;
  const double cu = dr / ((dr + su) * f), cv = dr / ((dr + sv) * f);
  return generatorsOf([&](const Eigen::Vector2d& image) {
    return std::pair{Eigen::Vector2d(image.x() * cu * su, image.y() * cv * sv),
                     Eigen::Vector2d(image.x() * cu * (su + 1.0), image.y() * cv * (sv + 1.0))};
  });
}

GlcParams photoParallaxGlc(const PhotoParallaxParams& p, double photo_focal) {
  requirePositive(photo_focal, "the photo's focal");
  if (!p.shift.allFinite() || !p.shift_per_u.allFinite() || !p.shift_per_v.allFinite())
    throw std::invalid_argument("parallax GLC: the shifts must be finite");
  const double f = photo_focal;
  // The ray of p' starts at −e(p')/f on z = 0 with the photo's direction (p'/f, 1).
  return generatorsOf([&](const Eigen::Vector2d& image) {
    const Eigen::Vector2d shift = p.shift + image.x() * p.shift_per_u + image.y() * p.shift_per_v;
    const Eigen::Vector2d st = -shift / f;
    return std::pair{st, Eigen::Vector2d(st + image / f)};
  });
}

Camera photoPushbroomCamera(const PhotoPushbroomParams& p, FrameSize frame) {
  return photoGlcCamera(photoPushbroomGlc(p, kPresetFocal), kPresetFocal, frame);
}
Camera photoXSlitCamera(const PhotoXSlitParams& p, FrameSize frame) {
  return photoGlcCamera(photoXSlitGlc(p, kPresetFocal), kPresetFocal, frame);
}
Camera photoParallaxCamera(const PhotoParallaxParams& p, FrameSize frame) {
  return photoGlcCamera(photoParallaxGlc(p, kPresetFocal), kPresetFocal, frame);
}

}  // namespace artcam
