// SPDX-License-Identifier: Apache-2.0
// The Fig 6 specular pair; see specular_pair.h.
#include "core/colour/specular_pair.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace artcam {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Surface {
  Eigen::Vector3d diffuse;  // body colour under the key light
  Eigen::Vector3d mirror;   // reflectance of the room (the specular reflection)
};

// Black velvet behind the reflectors, as in a product shot: the same in both photos, and black
// is where any colour map through the origin already sends black.
const Eigen::Vector3d kBackdrop(0.0, 0.0, 0.0);
const Eigen::Vector3d kKeyColour(1.0, 0.95, 0.9);
const Eigen::Vector3d kAmbient(0.05, 0.05, 0.05);
constexpr double kHighlight = 3.0;    // the key light's own reflection: far brighter than the room
constexpr double kShininess = 300.0;  // a tight highlight, as on polished metal and glass

// The room both reflectors stand in and reflect: a blue sky overhead, a red-brown floor, and
// between them a band of coloured walls (six hues round the horizon), so the silver surface
// reflects colours from all over the gamut — what pins a colour map down everywhere.
Eigen::Vector3d room(const Eigen::Vector3d& r) {
  if (r.y() > 0.35) {
    const double t = (r.y() - 0.35) / 0.65;
    return 0.6 * ((1.0 - t) * Eigen::Vector3d(0.45, 0.60, 0.85) + t * Eigen::Vector3d(0.12, 0.30, 0.90));
  }
  if (r.y() < -0.35) return 0.6 * Eigen::Vector3d(0.60, 0.26, 0.08);
  static const Eigen::Vector3d walls[6] = {{0.85, 0.15, 0.10}, {0.90, 0.75, 0.10},
                                           {0.20, 0.70, 0.20}, {0.10, 0.65, 0.75},
                                           {0.20, 0.20, 0.85}, {0.75, 0.20, 0.70}};
  const double at = (std::atan2(r.x(), r.z()) + kPi) / (2.0 * kPi) * 6.0;
  const int i = static_cast<int>(at) % 6;
  const double w = std::clamp((at - std::floor(at) - 0.8) / 0.2, 0.0, 1.0);  // soft wall edges
  return 0.6 * ((1.0 - w) * walls[i] + w * walls[(i + 1) % 6]);
}

Eigen::Vector3d shade(const Eigen::Vector3d& n, const Surface& s) {
  const Eigen::Vector3d view(0.0, 0.0, 1.0);
  const Eigen::Vector3d key = Eigen::Vector3d(-0.5, 0.6, 0.65).normalized();
  const Eigen::Vector3d r = 2.0 * n.dot(view) * n - view;
  const Eigen::Vector3d h = (key + view).normalized();
  const Eigen::Vector3d irradiance = kAmbient + std::max(0.0, n.dot(key)) * kKeyColour;
  return s.diffuse.cwiseProduct(irradiance) + s.mirror.cwiseProduct(room(r)) +
         kHighlight * std::pow(std::max(0.0, n.dot(h)), kShininess) * kKeyColour;
}

}  // namespace

SpecularPair makeSpecularPair(int size) {
  // Silver: almost all mirror, untinted. The bauble: a green glaze, its reflection of the room
  // tinted green and a little green body colour; both show the key light's highlight white.
  const Surface silver{{0.03, 0.03, 0.03}, {0.90, 0.90, 0.90}};
  const Surface green{{0.01, 0.06, 0.015}, {0.15, 0.75, 0.20}};
  SpecularPair pair;
  pair.silver = ImageF(size, size, 3);
  pair.green = ImageF(size, size, 3);
  pair.on_object.assign(static_cast<size_t>(size) * size, 0);
  const double radius = 0.42 * size, centre = 0.5 * size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Eigen::Vector3d sum_silver = Eigen::Vector3d::Zero(), sum_green = Eigen::Vector3d::Zero();
      int hits = 0;
      for (int sy = 0; sy < 3; ++sy)
        for (int sx = 0; sx < 3; ++sx) {
          const double px = (x + (sx + 0.5) / 3.0 - centre) / radius;
          const double py = -(y + (sy + 0.5) / 3.0 - centre) / radius;
          const double rr = px * px + py * py;
          if (rr >= 1.0) {
            sum_silver += kBackdrop;
            sum_green += kBackdrop;
            continue;
          }
          ++hits;
          const Eigen::Vector3d n(px, py, std::sqrt(1.0 - rr));
          // Clipped at 1 per channel, as a photo's highlights are: the core of the highlight is
          // the same white on both.
          sum_silver += shade(n, silver).cwiseMin(1.0);
          sum_green += shade(n, green).cwiseMin(1.0);
        }
      for (int c = 0; c < 3; ++c) {
        pair.silver.pixel(x, y)[c] = static_cast<float>(sum_silver[c] / 9.0);
        pair.green.pixel(x, y)[c] = static_cast<float>(sum_green[c] / 9.0);
      }
      pair.on_object[static_cast<size_t>(y) * size + x] = hits == 9;
    }
  return pair;
}

std::vector<PointMatch> specularSamples(const SpecularPair& pair, int stride) {
  std::vector<PointMatch> samples;
  const int w = pair.silver.width, h = pair.silver.height;
  const auto sample = [&](int x, int y) {
    PointMatch m;
    m.source = Eigen::Vector3d(pair.silver.pixel(x, y)[0], pair.silver.pixel(x, y)[1],
                               pair.silver.pixel(x, y)[2]);
    m.target = Eigen::Vector3d(pair.green.pixel(x, y)[0], pair.green.pixel(x, y)[1],
                               pair.green.pixel(x, y)[2]);
    samples.push_back(std::move(m));
  };
  for (int y = stride / 2; y < h; y += stride)
    for (int x = stride / 2; x < w; x += stride)
      if (pair.on_object[static_cast<size_t>(y) * w + x]) sample(x, y);
  sample(0, 0);  // the backdrop: black stays black
  return samples;
}

}  // namespace artcam
