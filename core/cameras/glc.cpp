// SPDX-License-Identifier: Apache-2.0
#include "core/cameras/glc.h"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

namespace artcam {

using tensor4::product;

namespace {

// A 2-vector of linear forms on (X, Y, Z, W).
struct Linear2 {
  Eigen::Vector4d x, y;
  Linear2 operator-(const Linear2& o) const { return {x - o.x, y - o.y}; }
};

// The quadratic form cross(a, b) = a.x·b.y - a.y·b.x.
Eigen::MatrixXd cross(const Linear2& a, const Linear2& b) {
  return product(a.x, b.y) - product(a.y, b.x);
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

GlcParams glcFromTwoPlanes(const std::array<Eigen::Vector4d, 3>& s_t_u_v, double focal) {
  GlcParams p;
  for (int i = 0; i < 3; ++i) {
    p.rays[i].st = s_t_u_v[i].head<2>();
    p.rays[i].uv = s_t_u_v[i].tail<2>();
    p.rays[i].image = focal * p.rays[i].uv;
  }
  return p;
}

Camera glcCamera(const GlcParams& p) {
  const auto& r = p.rays;
  if (std::abs(cross2(r[1].image - r[0].image, r[2].image - r[0].image)) <
      1e-12 * (r[1].image - r[0].image).squaredNorm() + 1e-300)
    throw std::invalid_argument("GLC: the three image points are collinear");
  if (!(p.far > 0)) throw std::invalid_argument("GLC far must be positive");

  // gᵢ scaled by W: W·stᵢ + Z·(uvᵢ - stᵢ).
  std::array<Linear2, 3> g;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d d = r[i].uv - r[i].st;
    g[i] = {Eigen::Vector4d(0, 0, d.x(), r[i].st.x()), Eigen::Vector4d(0, 0, d.y(), r[i].st.y())};
  }
  const Linear2 pt{tensor4::X(), tensor4::Y()};
  const Eigen::MatrixXd den = cross(g[1] - g[0], g[2] - g[0]);
  const std::array<Eigen::MatrixXd, 3> n = {
      cross(g[1] - pt, g[2] - pt), cross(g[2] - pt, g[0] - pt), cross(g[0] - pt, g[1] - pt)};

  // D = d2 Z² + d1 ZW + d0 W² (it involves only Z and W).
  const double d2 = den(2, 2), d1 = 2.0 * den(2, 3), d0 = den(3, 3);
  const double scale = std::max({std::abs(d2), std::abs(d1), std::abs(d0)});
  if (!(scale > 0))
    throw std::invalid_argument("GLC: the generator rays are degenerate (coplanar)");
  const double tol = 1e-12 * scale;
  double sign = 1.0;
  Eigen::MatrixXd nearness;
  if (std::abs(d2) > tol) {
    // Foci at the real roots of D (two slits, or a double root: a pinhole). With ρ the larger
    // root, (Z - ρW)W / D = 1/(|d2|(Z - ρ')) falls along every ray and is positive beyond the
    // nearer focus ρ' (in front of a pinhole). Complex roots (twisted GLCs): W²/D.
    sign = d2 > 0 ? 1.0 : -1.0;
    const double disc = d1 * d1 - 4.0 * d2 * d0;
    if (disc >= 0) {
      const double rho =
          std::max((-d1 + std::sqrt(disc)) / (2 * d2), (-d1 - std::sqrt(disc)) / (2 * d2));
      nearness = product(tensor4::linear(0, 0, 1, -rho), tensor4::W());
    } else {
      nearness = product(tensor4::W(), tensor4::W());
    }
  } else if (std::abs(d1) > tol) {
    // One focal plane (push-broom GLCs): D = d1·W(Z - ρW), nearness W²/D = 1/(|d1|(Z - ρ)).
    sign = d1 > 0 ? 1.0 : -1.0;
    nearness = product(tensor4::W(), tensor4::W());
  } else {
    sign = d0 > 0 ? 1.0 : -1.0;
    nearness = product(tensor4::linear(0, 0, -1.0 / p.far, 1), tensor4::W());
  }
  Eigen::MatrixXd zu = Eigen::MatrixXd::Zero(4, 4), zv = Eigen::MatrixXd::Zero(4, 4);
  for (int i = 0; i < 3; ++i) {
    zu += r[i].image.x() * n[i];
    zv += r[i].image.y() * n[i];
  }
  return objectCamera({sign * zu, sign * zv, nearness, sign * den}, p.pose);
}

Ray glcRay(const GlcParams& p, const Eigen::Vector2d& image) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) m.col(i) << p.rays[i].image, 1.0;
  const Eigen::Vector3d w = m.fullPivLu().solve(Eigen::Vector3d(image.x(), image.y(), 1.0));
  Eigen::Vector2d st = Eigen::Vector2d::Zero(), uv = Eigen::Vector2d::Zero();
  for (int i = 0; i < 3; ++i) {
    st += w[i] * p.rays[i].st;
    uv += w[i] * p.rays[i].uv;
  }
  return {p.pose.worldFromCamera(Eigen::Vector3d(st.x(), st.y(), 0)),
          p.pose.rotation.transpose() * Eigen::Vector3d(uv.x() - st.x(), uv.y() - st.y(), 1)};
}

}  // namespace artcam
