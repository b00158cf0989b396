// SPDX-License-Identifier: Apache-2.0
#include "core/fit/line_model_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace artcam {

namespace {

// The Jacobian's columns by central differences over one source pixel: the spacing a grid row
// and a grid column of the photo get in the target.
std::optional<Eigen::Vector2d> spacings(const Camera& camera, const Eigen::Vector2d& p) {
  const auto at = [&](double dx, double dy) {
    return targetPixelFromSourcePixel(camera, p + Eigen::Vector2d(dx, dy));
  };
  const auto xl = at(-1, 0), xh = at(1, 0), yl = at(0, -1), yh = at(0, 1);
  if (!xl || !xh || !yl || !yh) return std::nullopt;
  return Eigen::Vector2d((*xh - *xl).norm() / 2, (*yh - *yl).norm() / 2);
}

}  // namespace

double spacingChange(const Camera& candidate, const Camera& reference) {
  const FrameSize f = reference.sourceSize();
  double worst = 0.0;
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 9; ++i) {
      // Inset by 5 %: the frame's very edge is where a user has traced nothing.
      const Eigen::Vector2d p(f.width * (0.05 + 0.9 * i / 8.0), f.height * (0.05 + 0.9 * j / 6.0));
      const auto c = spacings(candidate, p), r = spacings(reference, p);
      if (!c || !r || !(r->minCoeff() > 0)) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, (c->array() / r->array() - 1.0).abs().maxCoeff());
    }
  return worst;
}

double frameCoverage(const Camera& camera) {
  const FrameSize s = camera.sourceSize(), t = camera.targetSize();
  const double cell = std::max(t.width, t.height) / 64.0;
  const int cw = std::max(1, static_cast<int>(std::ceil(t.width / cell)));
  const int ch = std::max(1, static_cast<int>(std::ceil(t.height / cell)));
  std::vector<char> hit(static_cast<size_t>(cw) * static_cast<size_t>(ch), 0);
  const double step = cell / 3.0;
  for (double y = step / 2; y < s.height; y += step)
    for (double x = step / 2; x < s.width; x += step) {
      const auto y_px = targetPixelFromSourcePixel(camera, {x, y});
      if (!y_px) continue;
      const double cx = std::floor(y_px->x() / cell), cy = std::floor(y_px->y() / cell);
      if (cx >= 0 && cy >= 0 && cx < cw && cy < ch)
        hit[static_cast<size_t>(cy) * static_cast<size_t>(cw) + static_cast<size_t>(cx)] = 1;
    }
  return static_cast<double>(std::count(hit.begin(), hit.end(), 1)) /
         static_cast<double>(hit.size());
}

}  // namespace artcam
