// SPDX-License-Identifier: Apache-2.0
#include "core/depth/stereo_house.h"

#include "core/util/parallel.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace artcam {
namespace {

// The house: walls x ∈ [−2, 2], z ∈ [−1.5, 1.5] up to the eaves at y = 2.2; a gable roof to the
// ridge at y = 3.2 over z = 0, overhanging 0.25 at the gable ends.
constexpr double kHalfX = 2.0, kHalfZ = 1.5, kEaves = 2.2, kRidge = 3.2, kOverhang = 0.25;

uint32_t hash3(int32_t x, int32_t y, int32_t z) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(y) * 0xd8163841u ^
               static_cast<uint32_t>(z) * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  return h ^ (h >> 15);
}

double lattice(int32_t x, int32_t y, int32_t salt) {
  return (hash3(x, y, salt) & 0xffffff) / 16777215.0;
}

// Smooth value noise in [0, 1] at unit lattice spacing.
double valueNoise(double u, double v, int32_t salt) {
  const double fu = std::floor(u), fv = std::floor(v);
  const auto iu = static_cast<int32_t>(fu), iv = static_cast<int32_t>(fv);
  double a = u - fu, b = v - fv;
  a = a * a * (3 - 2 * a);
  b = b * b * (3 - 2 * b);
  const double n00 = lattice(iu, iv, salt), n10 = lattice(iu + 1, iv, salt);
  const double n01 = lattice(iu, iv + 1, salt), n11 = lattice(iu + 1, iv + 1, salt);
  return (n00 * (1 - a) + n10 * a) * (1 - b) + (n01 * (1 - a) + n11 * a) * b;
}

// Detail at 0.4, 0.1 and 0.025 world units: every scale the pixels see has texture.
double grain(double u, double v, int32_t salt) {
  return 0.5 * valueNoise(u * 2.5, v * 2.5, salt) + 0.3 * valueNoise(u * 10, v * 10, salt + 1) +
         0.2 * valueNoise(u * 40, v * 40, salt + 2);
}

Eigen::Vector3d brick(double u, double v) {  // u along the wall, v up, world units
  const double row = std::floor(v / 0.18);
  const double shifted = u / 0.4 + (static_cast<int>(row) % 2 ? 0.5 : 0.0);
  const double col = std::floor(shifted);
  const bool mortar = v - row * 0.18 < 0.02 || shifted - col < 0.05;
  const double g = grain(u, v, 11);
  if (mortar) return Eigen::Vector3d(0.55, 0.53, 0.5) * (0.7 + 0.4 * g);
  const double tone = 0.75 + 0.5 * lattice(static_cast<int32_t>(col), static_cast<int32_t>(row), 7);
  return Eigen::Vector3d(0.45, 0.16, 0.09) * tone * (0.6 + 0.6 * g);
}

bool window(double u, double v, double length) {  // two windows per wall, 0.8 × 0.7
  for (double centre : {-0.25 * length, 0.25 * length})
    if (std::abs(u - centre) < 0.4 && v > 1.0 && v < 1.7) return true;
  return false;
}

Eigen::Vector3d windowColour(double u, double v) {
  const bool bar =
      std::abs(std::fmod(std::abs(u) + 0.2, 0.4) - 0.2) < 0.02 || std::abs(v - 1.35) < 0.02;
  return bar ? Eigen::Vector3d(0.8, 0.8, 0.75)
             : Eigen::Vector3d(0.05, 0.08, 0.12) * (0.6 + 0.8 * grain(u, v, 23));
}

Eigen::Vector3d tiles(double u, double s) {  // u along the ridge, s down the slope
  const double row = std::floor(s / 0.15);
  const double edge = s - row * 0.15;
  const double g = grain(u, s, 31);
  return Eigen::Vector3d(0.22, 0.2, 0.24) * (0.55 + 0.5 * g) * (edge < 0.025 ? 0.5 : 1.0);
}

Eigen::Vector3d grass(double x, double z) {
  const double g = grain(x, z, 41);
  return Eigen::Vector3d(0.12, 0.3, 0.07) * (0.5 + 0.8 * g);
}

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  Eigen::Vector3d colour{0, 0, 0};
};

// The nearest surface along o + t·d (t > 0), and its colour.
Hit trace(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  Hit best;
  auto consider = [&](double t, const Eigen::Vector3d& colour) {
    if (t > 1e-9 && t < best.t) {
      best.t = t;
      best.colour = colour;
    }
  };
  // Walls z = ±half_z and x = ±half_x (the gable triangles above the eaves on x = ±half_x).
  for (double zs : {kHalfZ, -kHalfZ}) {
    if (std::abs(d.z()) < 1e-12) continue;
    const double t = (zs - o.z()) / d.z();
    const Eigen::Vector3d p = o + t * d;
    if (std::abs(p.x()) <= kHalfX && p.y() >= 0 && p.y() <= kEaves) {
      const double u = p.x();
      consider(t, window(u, p.y(), 2 * kHalfX) ? windowColour(u, p.y()) : brick(u + 10, p.y()));
    }
  }
  for (double xs : {kHalfX, -kHalfX}) {
    if (std::abs(d.x()) < 1e-12) continue;
    const double t = (xs - o.x()) / d.x();
    const Eigen::Vector3d p = o + t * d;
    const double top = kEaves + (kRidge - kEaves) * (1.0 - std::abs(p.z()) / kHalfZ);
    if (std::abs(p.z()) <= kHalfZ && p.y() >= 0 && p.y() <= top) {
      const double u = -p.z() * (xs > 0 ? 1 : -1);
      consider(t, window(u, p.y(), 2 * kHalfZ) && p.y() < kEaves ? windowColour(u, p.y())
                                                                 : brick(u + 30, p.y()));
    }
  }
  // Roof slopes: y = ridge − (ridge − eaves)·|z| / half_z, |x| ≤ half_x + overhang.
  const double slope = (kRidge - kEaves) / kHalfZ;
  for (double side : {1.0, -1.0}) {
    // y + slope·side·z = ridge
    const double denom = d.y() + slope * side * d.z();
    if (std::abs(denom) < 1e-12) continue;
    const double t = (kRidge - o.y() - slope * side * o.z()) / denom;
    const Eigen::Vector3d p = o + t * d;
    if (side * p.z() >= 0 && side * p.z() <= kHalfZ + 0.2 && std::abs(p.x()) <= kHalfX + kOverhang)
      consider(t, tiles(p.x(), side * p.z() * std::sqrt(1 + slope * slope)));
  }
  // The lawn.
  if (d.y() < -1e-12) {
    const double t = -o.y() / d.y();
    const Eigen::Vector3d p = o + t * d;
    if (std::abs(p.x()) < 60 && std::abs(p.z()) < 60) consider(t, grass(p.x(), p.z()));
  }
  return best;
}

Eigen::Vector3d sky(const Eigen::Vector3d& d) {
  const double up = std::clamp(d.normalized().y(), 0.0, 1.0);
  return Eigen::Vector3d(0.55, 0.7, 0.95) * (1.0 - 0.4 * up);
}

Eigen::Vector3d rayThrough(const StereoHouseScene& s, double x, double y) {
  return s.forward() + (x - 0.5 * s.width) / s.focal_px * s.right() +
         (y - 0.5 * s.height) / s.focal_px * s.down();
}

ImageF renderView(const StereoHouseScene& s, const Eigen::Vector3d& eye, ImageF* depth) {
  ImageF image(s.width, s.height, 3);
  if (depth) *depth = ImageF(s.width, s.height, 1);
  const int n = std::max(1, s.supersample);
  parallelForRows(s.height, ParallelOptions{}, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < s.width; ++x) {
        Eigen::Vector3d sum(0, 0, 0);
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const Eigen::Vector3d d = rayThrough(s, x + (i + 0.5) / n, y + (j + 0.5) / n);
            const Hit h = trace(eye, d);
            sum += std::isfinite(h.t) ? h.colour : sky(d);
          }
        sum /= n * n;
        float* p = image.pixel(x, y);
        for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(sum[k]);
        if (depth) {
          // The ray's forward component is 1, so its parameter is the depth along the view axis.
          const Hit h = trace(eye, rayThrough(s, x + 0.5, y + 0.5));
          *depth->pixel(x, y) = std::isfinite(h.t) ? static_cast<float>(h.t) : 0.0f;
        }
      }
  });
  return image;
}

}  // namespace

Eigen::Vector3d StereoHouseScene::forward() const { return (look_at - left_eye).normalized(); }
Eigen::Vector3d StereoHouseScene::right() const {
  return forward().cross(Eigen::Vector3d::UnitY()).normalized();
}
Eigen::Vector3d StereoHouseScene::down() const { return forward().cross(right()).normalized(); }

Eigen::Vector3d stereoHouseColourAlong(const Eigen::Vector3d& origin,
                                       const Eigen::Vector3d& direction) {
  const Hit h = trace(origin, direction);
  return std::isfinite(h.t) ? h.colour : sky(direction);
}

StereoHousePair renderStereoHouse(const StereoHouseScene& scene) {
  StereoHousePair pair;
  pair.left = renderView(scene, scene.left_eye, &pair.left_depth);
  pair.right = renderView(scene, scene.left_eye + scene.baseline * scene.right(), nullptr);
  auto project = [&](const Eigen::Vector3d& X) {
    const Eigen::Vector3d v = X - scene.left_eye;
    const double z = v.dot(scene.forward());
    return Eigen::Vector2d(0.5 * scene.width + scene.focal_px * v.dot(scene.right()) / z,
                           0.5 * scene.height + scene.focal_px * v.dot(scene.down()) / z);
  };
  // The walls the left eye sees (it stands at +x, +z): the front (z = +half_z) and the +x side
  // with its gable, each in order around the wall as a user would mark it.
  pair.walls.push_back({"front",
                        {{-kHalfX, 0, kHalfZ},
                         {kHalfX, 0, kHalfZ},
                         {kHalfX, kEaves, kHalfZ},
                         {-kHalfX, kEaves, kHalfZ}},
                        {}});
  pair.walls.push_back({"side",
                        {{kHalfX, 0, kHalfZ},
                         {kHalfX, 0, -kHalfZ},
                         {kHalfX, kEaves, -kHalfZ},
                         {kHalfX, kRidge, 0},
                         {kHalfX, kEaves, kHalfZ}},
                        {}});
  for (HouseWall& w : pair.walls)
    for (const Eigen::Vector3d& c : w.corners) w.left_px.push_back(project(c));
  return pair;
}

}  // namespace artcam
