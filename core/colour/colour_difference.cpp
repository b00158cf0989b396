// SPDX-License-Identifier: Apache-2.0
#include "core/colour/colour_difference.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace artcam {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// IEC 61966-2-1 linear sRGB → XYZ (D65).
const Eigen::Matrix3d& xyzFromRgbMatrix() {
  static const Eigen::Matrix3d m = (Eigen::Matrix3d() << 0.4124, 0.3576, 0.1805,  //
                                    0.2126, 0.7152, 0.0722,                       //
                                    0.0193, 0.1192, 0.9505)
                                       .finished();
  return m;
}

// CIELAB's f(t): the cube root above (6/29)³, its tangent line below (also for t < 0, which
// out-of-gamut linear data can produce; the cube root would be defined but not the standard).
double labF(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

// Hue angle in degrees, [0, 360); 0 for the neutral axis (a = b = 0), as the notes specify.
double hueDegrees(double b, double a) {
  if (a == 0.0 && b == 0.0) return 0.0;
  const double h = std::atan2(b, a) / kDegree;
  return h < 0.0 ? h + 360.0 : h;
}

double pow7(double x) {
  const double x2 = x * x;
  return x2 * x2 * x2 * x;
}

}  // namespace

Eigen::Vector3d xyzFromLinearRgb(const Eigen::Vector3d& rgb) { return xyzFromRgbMatrix() * rgb; }

Lab labFromXyz(const Eigen::Vector3d& xyz) {
  const Eigen::Vector3d white = xyzFromRgbMatrix() * Eigen::Vector3d::Ones();
  const double fx = labF(xyz.x() / white.x());
  const double fy = labF(xyz.y() / white.y());
  const double fz = labF(xyz.z() / white.z());
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab labFromLinearRgb(const Eigen::Vector3d& rgb) { return labFromXyz(xyzFromLinearRgb(rgb)); }

double ciede2000(const Lab& first, const Lab& second) {
  // Sharma, Wu & Dalal (2005), eqs 1–22 of their notes.
  const double c1 = std::hypot(first.a, first.b), c2 = std::hypot(second.a, second.b);
  const double c_mean7 = pow7(0.5 * (c1 + c2));
  const double g = 0.5 * (1.0 - std::sqrt(c_mean7 / (c_mean7 + pow7(25.0))));
  const double a1 = (1.0 + g) * first.a, a2 = (1.0 + g) * second.a;
  const double cp1 = std::hypot(a1, first.b), cp2 = std::hypot(a2, second.b);
  const double hp1 = hueDegrees(first.b, a1), hp2 = hueDegrees(second.b, a2);

  const double dl = second.l - first.l;
  const double dc = cp2 - cp1;
  double dh = 0.0;
  if (cp1 * cp2 != 0.0) {
    dh = hp2 - hp1;
    if (dh > 180.0) dh -= 360.0;
    else if (dh < -180.0) dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(0.5 * dh * kDegree);

  const double l_mean = 0.5 * (first.l + second.l);
  const double cp_mean = 0.5 * (cp1 + cp2);
  double h_mean = hp1 + hp2;
  if (cp1 * cp2 != 0.0) {
    if (std::abs(hp1 - hp2) <= 180.0) h_mean = 0.5 * (hp1 + hp2);
    else if (hp1 + hp2 < 360.0) h_mean = 0.5 * (hp1 + hp2 + 360.0);
    else h_mean = 0.5 * (hp1 + hp2 - 360.0);
  }
  const double t = 1.0 - 0.17 * std::cos((h_mean - 30.0) * kDegree) +
                   0.24 * std::cos(2.0 * h_mean * kDegree) +
                   0.32 * std::cos((3.0 * h_mean + 6.0) * kDegree) -
                   0.20 * std::cos((4.0 * h_mean - 63.0) * kDegree);
  const double d_theta = 30.0 * std::exp(-std::pow((h_mean - 275.0) / 25.0, 2.0));
  const double cp_mean7 = pow7(cp_mean);
  const double r_c = 2.0 * std::sqrt(cp_mean7 / (cp_mean7 + pow7(25.0)));
  const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
  const double s_l = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double s_c = 1.0 + 0.045 * cp_mean;
  const double s_h = 1.0 + 0.015 * cp_mean * t;
  const double r_t = -std::sin(2.0 * d_theta * kDegree) * r_c;
  const double tl = dl / s_l, tc = dc / s_c, th = dH / s_h;
  // The rotation term can make the sum dip a hair below zero for tiny differences.
  return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + r_t * tc * th));
}

double deltaE2000(const Eigen::Vector3d& rgb_first, const Eigen::Vector3d& rgb_second) {
  return ciede2000(labFromLinearRgb(rgb_first), labFromLinearRgb(rgb_second));
}

}  // namespace artcam
