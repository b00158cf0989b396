// SPDX-License-Identifier: Apache-2.0
// Checkerboard corner snapping; see corner_snap.h.
#include "core/piecewise/corner_snap.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace artcam {
namespace {

// A square of luminance around a point, Gaussian-smoothed, with its Hessian determinant and
// gradient; pixel (i, j) has its centre at (x0 + i + 0.5, y0 + j + 0.5).
struct Window {
  int x0 = 0, y0 = 0, size = 0;
  std::vector<double> lum, gx, gy, det;
  double at(const std::vector<double>& v, int i, int j) const {
    return v[static_cast<size_t>(j) * static_cast<size_t>(size) + static_cast<size_t>(i)];
  }
};

double luminance(const ImageF& image, int x, int y) {
  x = std::clamp(x, 0, image.width - 1);
  y = std::clamp(y, 0, image.height - 1);
  const float* p = image.pixel(x, y);
  if (image.channels >= 3) return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  return p[0];
}

template <class Sample>
Window makeWindow(int x0, int y0, int size, double sigma, Sample sample) {
  Window w;
  w.x0 = x0, w.y0 = y0, w.size = size;
  const size_t n = static_cast<size_t>(size) * static_cast<size_t>(size);
  std::vector<double> raw(n), tmp(n);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) raw[static_cast<size_t>(j * size + i)] = sample(x0 + i, y0 + j);
  const int r = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<double> k(static_cast<size_t>(2 * r + 1));
  double sum = 0;
  for (int t = -r; t <= r; ++t) sum += k[static_cast<size_t>(t + r)] = std::exp(-0.5 * t * t / (sigma * sigma));
  for (double& v : k) v /= sum;
  const auto idx = [size](int i, int j) {
    return static_cast<size_t>(std::clamp(j, 0, size - 1) * size + std::clamp(i, 0, size - 1));
  };
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      double s = 0;
      for (int t = -r; t <= r; ++t) s += k[static_cast<size_t>(t + r)] * raw[idx(i + t, j)];
      tmp[static_cast<size_t>(j * size + i)] = s;
    }
  w.lum.assign(n, 0.0);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      double s = 0;
      for (int t = -r; t <= r; ++t) s += k[static_cast<size_t>(t + r)] * tmp[idx(i, j + t)];
      w.lum[static_cast<size_t>(j * size + i)] = s;
    }
  w.gx.assign(n, 0.0), w.gy.assign(n, 0.0), w.det.assign(n, 0.0);
  for (int j = 1; j + 1 < size; ++j)
    for (int i = 1; i + 1 < size; ++i) {
      const auto L = [&](int a, int b) { return w.lum[static_cast<size_t>((j + b) * size + i + a)]; };
      const size_t c = static_cast<size_t>(j * size + i);
      w.gx[c] = 0.5 * (L(1, 0) - L(-1, 0));
      w.gy[c] = 0.5 * (L(0, 1) - L(0, -1));
      const double xx = L(1, 0) - 2 * L(0, 0) + L(-1, 0);
      const double yy = L(0, 1) - 2 * L(0, 0) + L(0, -1);
      const double xy = 0.25 * (L(1, 1) - L(1, -1) - L(-1, 1) + L(-1, -1));
      w.det[c] = xx * yy - xy * xy;
    }
  return w;
}

// The most negative Hessian determinant of an ideal unit-contrast corner after the same
// smoothing: the yardstick for "clearly a corner".
double idealSaddle(double sigma) {
  const int size = 2 * static_cast<int>(std::ceil(3 * sigma)) + 9;
  const double c = 0.5 * size;
  const Window w = makeWindow(0, 0, size, sigma, [c](int x, int y) {
    double v = 0;  // 4×4 supersampled box filter, as a rendered board would be
    for (int s = 0; s < 16; ++s) {
      const double px = x + (s % 4 + 0.5) / 4 - c, py = y + (s / 4 + 0.5) / 4 - c;
      v += (px < 0) == (py < 0) ? 1.0 : 0.0;
    }
    return v / 16;
  });
  return *std::min_element(w.det.begin(), w.det.end());
}

}  // namespace

std::optional<Eigen::Vector2d> snapToGridCorner(const ImageF& image, const Eigen::Vector2d& click,
                                                const CornerSnapOptions& o) {
  if (image.empty() || !click.allFinite()) return std::nullopt;
  const double sigma = std::max(0.3, o.smoothing_sigma_px);
  const int half = static_cast<int>(std::ceil(o.search_radius_px + o.window_radius_px + 3 * sigma)) + 2;
  const int cx = static_cast<int>(std::floor(click.x())), cy = static_cast<int>(std::floor(click.y()));
  const Window w = makeWindow(cx - half, cy - half, 2 * half + 1, sigma,
                              [&image](int x, int y) { return luminance(image, x, y); });

  // Contrast of the neighbourhood, so the saddle test does not depend on exposure.
  const auto [lo, hi] = std::minmax_element(w.lum.begin(), w.lum.end());
  const double contrast = *hi - *lo;
  if (!(contrast > std::max(1e-6, o.min_contrast))) return std::nullopt;

  int best_i = -1, best_j = -1;
  double best = 0.0;
  for (int j = 1; j + 1 < w.size; ++j)
    for (int i = 1; i + 1 < w.size; ++i) {
      const Eigen::Vector2d p(w.x0 + i + 0.5, w.y0 + j + 0.5);
      if ((p - click).norm() > o.search_radius_px) continue;
      const double d = w.at(w.det, i, j);
      if (d < best) best = d, best_i = i, best_j = j;
    }
  static const double kIdeal = idealSaddle(1.0);
  const double ideal = sigma == 1.0 ? kIdeal : idealSaddle(sigma);
  if (best_i < 0 || best / (contrast * contrast) > o.min_strength * ideal) return std::nullopt;

  // Gradient-orthogonality refinement: minimise Σ w (g·(p − c))² over c.
  Eigen::Vector2d c(w.x0 + best_i + 0.5, w.y0 + best_j + 0.5);
  const double spread = std::max(1.0, 0.5 * o.window_radius_px);
  for (int it = 0; it < 40; ++it) {
    Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    for (int j = 1; j + 1 < w.size; ++j)
      for (int i = 1; i + 1 < w.size; ++i) {
        const Eigen::Vector2d p(w.x0 + i + 0.5, w.y0 + j + 0.5);
        const double r2 = (p - c).squaredNorm();
        if (r2 > o.window_radius_px * o.window_radius_px) continue;
        const Eigen::Vector2d g(w.at(w.gx, i, j), w.at(w.gy, i, j));
        const Eigen::Matrix2d ggt = std::exp(-0.5 * r2 / (spread * spread)) * g * g.transpose();
        a += ggt;
        b += ggt * p;
      }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(a);
    // Two gradient directions are needed: an edge alone leaves c free along it.
    if (!(eig.eigenvalues()[0] > 0.05 * eig.eigenvalues()[1])) return std::nullopt;
    const Eigen::Vector2d next = a.ldlt().solve(b);
    if (!next.allFinite()) return std::nullopt;
    const double step = (next - c).norm();
    c = next;
    if ((c - click).norm() > o.search_radius_px + 1.0) return std::nullopt;
    if (step < 1e-4) return c;
  }
  return c;
}

}  // namespace artcam
