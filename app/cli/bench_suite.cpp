// SPDX-License-Identifier: Apache-2.0
#include "app/cli/bench_suite.h"

#include "core/effects/effect_table.h"
#include "core/fit/fit_image.h"
#include "core/model/structure.h"
#include "core/piecewise/piecewise_fit.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

namespace artcam::cli {
namespace {

// Matches photo (as shot) → corrected photo for a radial model given as the corrected radius
// of a photo radius, both in pixels from the frame centre, on a grid over the photo.
std::vector<PointMatch> radialMatches(FrameSize size, const std::function<double(double)>& corrected,
                                      int nx, int ny) {
  std::vector<PointMatch> matches;
  const double cx = size.width / 2.0, cy = size.height / 2.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d s((i + 0.5) * size.width / nx, (j + 0.5) * size.height / ny);
      const Eigen::Vector2d d = s - Eigen::Vector2d(cx, cy);
      const double r = d.norm();
      const Eigen::Vector2d t = Eigen::Vector2d(cx, cy) + (r > 0 ? d * (corrected(r) / r) : d);
      PointMatch m;
      m.source = s;
      m.target = t;
      matches.push_back(m);
    }
  return matches;
}

// lensfun's poly5 a(r) = r (1 + k1 r² + k2 r⁴) gives the photo radius of a corrected radius,
// r in units of half the shorter side; the corrected radius of a photo radius by Newton.
std::function<double(double)> poly5Corrected(FrameSize size, double k1, double k2) {
  const double unit = std::min(size.width, size.height) / 2.0;
  return [=](double r_px) {
    const double rd = r_px / unit;
    double ru = rd;
    for (int k = 0; k < 50; ++k) {
      const double r2 = ru * ru;
      const double f = ru * (1 + k1 * r2 + k2 * r2 * r2) - rd;
      const double df = 1 + 3 * k1 * r2 + 5 * k2 * r2 * r2;
      ru -= f / df;
    }
    return ru * unit;
  };
}

// An equisolid fisheye (r = 2 f sin(θ/2)) to rectilinear (r = f tan θ) with the same f, the
// photo's corner at `corner_deg` off axis.
std::function<double(double)> fisheyeCorrected(FrameSize size, double corner_deg) {
  const double corner = std::hypot(size.width, size.height) / 2.0;
  const double f = corner / (2.0 * std::sin(corner_deg * M_PI / 360.0));
  return [=](double r_px) { return f * std::tan(2.0 * std::asin(r_px / (2.0 * f))); };
}

Artcam quadraticFit(const std::vector<PointMatch>& matches, FrameSize size, const char* name) {
  FitOptions options;
  options.model = ModelClass::Quadratic;
  options.diagnostics = false;
  const FitSummary fit = fitImageCamera(matches, size, size, options);
  if (!fit.status.ok)
    throw std::runtime_error(std::string("bench suite: ") + name + ": " + fit.status.message);
  return Artcam(fit.camera);
}

}  // namespace

std::vector<SuiteCamera> benchCameraSuite(FrameSize size) {
  std::vector<SuiteCamera> suite;
  {
    Eigen::Matrix3d h;
    h << 1.02, 0.05, 0.01, -0.04, 0.99, -0.02, 0.03, -0.02, 1;
    Stage stage;
    for (const Eigen::MatrixXd& q : liftHomography(h)) stage.q.push_back(q);
    suite.push_back({"homography", Artcam(Camera({Block{BlockKind::Position, 3}}, {stage}, size, size))});
  }
  // A compact zoom's wide end (~180 px of distortion at a 6000×4000 corner), a strong wide
  // angle with the moustache of a positive k2 (~560 px), an equisolid fisheye (corner 60°).
  const auto compact = poly5Corrected(size, -0.015, 0.0);
  const auto wide = poly5Corrected(size, -0.08, 0.01);
  const auto fisheye = fisheyeCorrected(size, 60.0);
  suite.push_back({"lens-compact", quadraticFit(radialMatches(size, compact, 25, 17), size, "lens-compact")});
  suite.push_back({"lens-wide", quadraticFit(radialMatches(size, wide, 25, 17), size, "lens-wide")});
  suite.push_back({"fisheye", quadraticFit(radialMatches(size, fisheye, 25, 17), size, "fisheye")});
  const struct {
    const char* name;
    const char* effect;
    EffectValues values;
  } presets[] = {
      {"barrel", "barrel", {}},
      {"barrel-strong", "barrel", {{"k", {-0.6}}}},
      {"pincushion", "pincushion", {}},
      {"pincushion-strong", "pincushion", {{"k", {0.45}}}},
      {"twist", "twist", {}},
      {"twist-strong", "twist", {{"rate", {1.0}}}},
      {"inverse-perspective", "inverse-perspective", {}},
      {"inverse-perspective-strong", "inverse-perspective", {{"gain", {0.85}}}},
      {"chromatic-aberration", "chromatic-aberration", {}},
      {"chromatic-aberration-strong", "chromatic-aberration", {{"red", {0.05}}, {"blue", {-0.05}}}},
  };
  for (const auto& p : presets) suite.push_back({p.name, buildEffect(p.effect, p.values, size)});
  {
    PiecewiseOptions options;
    options.max_error_px = 0.5;
    const PiecewiseSummary fit = fitPiecewise(radialMatches(size, fisheye, 61, 41), size, size, options);
    if (!fit.status.ok) throw std::runtime_error("bench suite: piecewise: " + fit.status.message);
    Artcam camera(fit.camera.patches.front().camera);
    camera.pieces = fit.camera;
    suite.push_back({"piecewise", std::move(camera)});
  }
  return suite;
}

}  // namespace artcam::cli
