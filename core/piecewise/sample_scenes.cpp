// SPDX-License-Identifier: Apache-2.0
// Bundled sample scenes for environment matting; see sample_scenes.h.
#include "core/piecewise/sample_scenes.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <limits>

namespace artcam {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d checker(const Eigen::Vector2d& g, int size, int squares) {
  if (g.x() < 0 || g.y() < 0 || g.x() > size || g.y() > size)
    return {0.42, 0.30, 0.20};  // the table beyond the grid
  const double cell = static_cast<double>(size) / squares;
  const int i = static_cast<int>(g.x() / cell), j = static_cast<int>(g.y() / cell);
  return (i + j) % 2 ? Eigen::Vector3d(0.85, 0.85, 0.82) : Eigen::Vector3d(0.06, 0.06, 0.07);
}

Eigen::Vector3d sky(double y, int height) {
  const double t = std::clamp(y / height, 0.0, 1.0);
  return (1 - t) * Eigen::Vector3d(0.25, 0.45, 0.85) + t * Eigen::Vector3d(0.75, 0.82, 0.92);
}

template <class Scene>
ImageF renderPhoto(const Scene& scene, int squares, const Eigen::Vector3d& object_tint) {
  ImageF photo(scene.photo_width, scene.photo_height, 3);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int sy = 0; sy < 3; ++sy)
        for (int sx = 0; sx < 3; ++sx) {
          const Eigen::Vector2d p(x + (sx + 0.5) / 3.0, y + (sy + 0.5) / 3.0);
          const TracedRay r = scene.trace(p);
          Eigen::Vector3d c = r.on_plane ? checker(r.plane_px, scene.graphic_size, squares)
                                         : sky(p.y(), photo.height);
          if (r.through_object) c = c.cwiseProduct(object_tint);
          sum += c;
        }
      float* out = photo.pixel(x, y);
      for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(sum[c] / 9.0);
    }
  return photo;
}

// Photo pixel where the grid corner `g` is seen through the object: start at the traced pixel
// nearest to it, then Newton on p ↦ graphicFromPhoto(p) with a central-difference Jacobian.
template <class Scene>
std::optional<Eigen::Vector2d> photoOfCorner(const Scene& scene, const Eigen::Vector2d& g,
                                             const std::vector<Eigen::Vector2d>& starts_photo,
                                             const std::vector<Eigen::Vector2d>& starts_graphic) {
  size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < starts_graphic.size(); ++k) {
    const double d = (starts_graphic[k] - g).squaredNorm();
    if (d < best_d) best_d = d, best = k;
  }
  if (starts_graphic.empty()) return std::nullopt;
  Eigen::Vector2d p = starts_photo[best];
  const double h = 0.05;
  for (int it = 0; it < 20; ++it) {
    const auto f = scene.graphicFromPhoto(p);
    if (!f) return std::nullopt;
    const Eigen::Vector2d r = *f - g;
    if (r.norm() < 1e-6) return p;
    Eigen::Matrix2d j;
    for (int a = 0; a < 2; ++a) {
      const Eigen::Vector2d e = Eigen::Vector2d::Unit(a) * h;
      const auto fp = scene.graphicFromPhoto(p + e), fm = scene.graphicFromPhoto(p - e);
      if (!fp || !fm) return std::nullopt;
      j.col(a) = (*fp - *fm) / (2 * h);
    }
    if (std::abs(j.determinant()) < 1e-12) return std::nullopt;
    p -= j.inverse() * r;
    if (p.x() < 0 || p.y() < 0 || p.x() > scene.photo_width || p.y() > scene.photo_height)
      return std::nullopt;
  }
  return std::nullopt;
}

template <class Scene>
SampleScene makeSample(const Scene& scene, int squares, const Eigen::Vector3d& tint) {
  SampleScene out;
  out.photo = renderPhoto(scene, squares, tint);
  std::vector<Eigen::Vector2d> photo_px, graphic_px;
  for (int y = 0; y < scene.photo_height; ++y)
    for (int x = 0; x < scene.photo_width; ++x)
      if (const auto g = scene.graphicFromPhoto({x + 0.5, y + 0.5})) {
        photo_px.emplace_back(x + 0.5, y + 0.5);
        graphic_px.push_back(*g);
      }
  const double cell = static_cast<double>(scene.graphic_size) / squares;
  for (int j = 0; j <= squares; ++j)
    for (int i = 0; i <= squares; ++i) {
      const Eigen::Vector2d g(i * cell, j * cell);
      if (const auto p = photoOfCorner(scene, g, photo_px, graphic_px)) {
        PointMatch m;
        m.source = g;
        m.target = *p;
        out.grid_matches.push_back(m);
      }
    }
  return out;
}

// The object's outline: from a point inside it, along `vertices` directions, the last photo
// position whose ray still meets the object, by bisection (the silhouette is star-shaped about
// the sphere's centre seen in the photo).
template <class Scene>
std::vector<Eigen::Vector2d> objectOutline(const Scene& scene, const Eigen::Vector2d& inside,
                                           int vertices) {
  std::vector<Eigen::Vector2d> outline;
  const double reach = std::hypot(scene.photo_width, scene.photo_height);
  for (int k = 0; k < vertices; ++k) {
    const double a = 2.0 * kPi * k / vertices;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    double lo = 0.0, hi = reach;
    while (hi - lo > 1e-6) {
      const double mid = 0.5 * (lo + hi);
      (scene.trace(inside + mid * dir).through_object ? lo : hi) = mid;
    }
    outline.push_back(inside + lo * dir);
  }
  return outline;
}

}  // namespace

SampleScene makeMirrorSphereSample(const MirrorSphereScene& scene, int squares) {
  SampleScene out = makeSample(scene, squares, {0.9, 0.9, 0.92});  // a slightly cool chrome
  // The user's clicks: four grid corners seen directly, as far apart as the frame allows (the
  // visible corners extreme in i + j and i − j: near the board's four corners).
  const double cell = static_cast<double>(scene.graphic_size) / squares;
  std::array<std::optional<std::pair<int, int>>, 4> extremes;  // min i+j, max i−j, max i+j, min i−j
  const auto score = [](int k, int i, int j) {
    return k == 0 ? -(i + j) : k == 1 ? i - j : k == 2 ? i + j : j - i;
  };
  for (int j = 0; j <= squares; ++j)
    for (int i = 0; i <= squares; ++i) {
      const Eigen::Vector2d p = scene.photoFromWorld(scene.floorFromGraphicPx({i * cell, j * cell}));
      if (p.x() < 0 || p.y() < 0 || p.x() > scene.photo_width || p.y() > scene.photo_height) continue;
      if (scene.trace(p).through_object) continue;  // hidden behind the sphere
      for (int k = 0; k < 4; ++k)
        if (!extremes[k] || score(k, i, j) > score(k, extremes[k]->first, extremes[k]->second))
          extremes[k] = {i, j};
    }
  for (const auto& corner : extremes) {
    if (!corner) continue;
    const Eigen::Vector2d g(corner->first * cell, corner->second * cell);
    PointMatch m;
    m.source = g;
    m.target = scene.photoFromWorld(scene.floorFromGraphicPx(g));
    out.table_matches.push_back(m);
  }
  out.region = objectOutline(scene, scene.objectCentrePx(), 256);
  return out;
}

SampleScene makeWaterGlassSample(const WaterGlassScene& scene, int squares) {
  return makeSample(scene, squares, {0.88, 0.95, 0.97});  // water absorbs a little red
}

SampleScene makeGlassOfWaterSample(GlassOfWaterScene scene, int squares) {
  scene.medium = GlassOfWaterScene::Medium::Water;
  SampleScene out = makeSample(scene, squares, {0.9, 0.96, 0.98});  // glass and water, faintly
  scene.medium = GlassOfWaterScene::Medium::Air;
  out.air_matches = makeSample(scene, squares, {0.9, 0.96, 0.98}).grid_matches;
  return out;
}

ImageF makeEmblemGraphic(int size) {
  ImageF g(size, size, 4, 3);
  const double c = 0.5 * size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // 4×4 supersampled coverage of a ring and a five-pointed star.
      double cover_ring = 0, cover_star = 0;
      for (int s = 0; s < 16; ++s) {
        const double px = x + (s % 4 + 0.5) / 4 - c, py = y + (s / 4 + 0.5) / 4 - c;
        const double r = std::hypot(px, py) / c, a = std::atan2(py, px);
        if (r > 0.78 && r < 0.95) cover_ring += 1;
        const double spoke = std::cos(5 * (a + kPi / 2)) * 0.5 + 0.5;  // 1 at the points
        if (r < 0.3 + 0.38 * std::pow(spoke, 3)) cover_star += 1;
      }
      cover_ring /= 16, cover_star /= 16;
      const double hue = std::atan2(y - c, x - c) / (2 * kPi) + 0.5;
      const Eigen::Vector3d ring(0.5 + 0.5 * std::cos(2 * kPi * hue), 0.5 + 0.5 * std::cos(2 * kPi * (hue - 1.0 / 3)),
                                 0.5 + 0.5 * std::cos(2 * kPi * (hue - 2.0 / 3)));
      const Eigen::Vector3d star(0.95, 0.75, 0.05);
      const double alpha = std::min(1.0, cover_ring + cover_star);
      const Eigen::Vector3d premult = cover_ring * ring + cover_star * star;
      float* p = g.pixel(x, y);
      for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(std::min(premult[k], alpha));
      p[3] = static_cast<float>(alpha);
    }
  return g;
}

}  // namespace artcam
