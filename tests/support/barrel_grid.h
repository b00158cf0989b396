// SPDX-License-Identifier: Apache-2.0
// A square grid of 90 px on a 960×720 photo seen through a barrel lens, made outside the code
// under test, with the plumb lines a user traces on it and the tests' own check of a camera
// against the grid's truth. The lens is one of two kinds: the division lens of the project's own
// barrel pictures, scene = u / (1 - k |u|²) in the normalised frame (photo points by the
// closed-form inverse, straight_lines.h), or a polynomial in the SCENE radius, photo = c +
// (s - c)(1 + k ρ²) with ρ = |s - c| / 600 px, a different family from the line fit's, which it
// can only approximate, as with a real lens. Pixels have centres at i + 0.5.
#pragma once

#include "core/model/camera.h"
#include "core/model/frames.h"
#include "core/model/line_trace.h"
#include "tests/support/straight_lines.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace artcam::test {

struct BarrelGrid {
  FrameSize frame{960, 720};
  Eigen::Vector2d centre{480, 360};
  double spacing_px = 90.0;  // the truth: neighbouring grid lines in the scene
  bool division = true;
  double k = 0.25;  // division: k > 0 is barrel; polynomial: k < 0 is barrel

  Eigen::Vector2d photoFromScene(const Eigen::Vector2d& scene_px) const {
    if (division)
      return pixelFromNormalized(frame,
                                 radialPhotoFromScene(k, normalizedFromPixel(frame, scene_px)));
    const Eigen::Vector2d d = scene_px - centre;
    return centre + d * (1 + k * d.squaredNorm() / (600.0 * 600.0));
  }

  bool inPhoto(const Eigen::Vector2d& p) const {
    return p.x() >= 0 && p.y() >= 0 && p.x() <= frame.width && p.y() <= frame.height;
  }

  // Grid line `at` (a scene x for a vertical, y for a horizontal) traced as a user clicks it:
  // 8 points spread along it, those the photo shows, with a quarter pixel of hand noise.
  LineTrace traced(const std::string& label, bool horizontal, double at_px,
                   std::mt19937& rng) const {
    std::normal_distribution<double> hand(0.0, 0.25);
    LineTrace line;
    line.label = label;
    const int clicks = 8;
    const double length = horizontal ? frame.width : frame.height;
    for (int i = 0; i < clicks; ++i) {
      const double along = 20 + (length - 40) * i / (clicks - 1.0);
      const Eigen::Vector2d s =
          horizontal ? Eigen::Vector2d(along, at_px) : Eigen::Vector2d(at_px, along);
      const Eigen::Vector2d p = photoFromScene(s) + Eigen::Vector2d(hand(rng), hand(rng));
      if (inPhoto(p)) line.points.push_back(p);
    }
    return line;
  }

  // The textbook plumb-line set: two horizontals three grid lines above and below the centre,
  // and (with_verticals) two verticals four grid lines left and right of it.
  std::vector<LineTrace> plumbLines(bool with_verticals, int seed) const {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::vector<LineTrace> lines = {traced("top", true, centre.y() - 3 * spacing_px, rng),
                                    traced("bottom", true, centre.y() + 3 * spacing_px, rng)};
    if (with_verticals) {
      lines.push_back(traced("left", false, centre.x() - 4 * spacing_px, rng));
      lines.push_back(traced("right", false, centre.x() + 4 * spacing_px, rng));
    }
    return lines;
  }

  struct Check {
    double worst_ratio_error = 0;  // max |spacing / truth - 1| over neighbouring nodes
    double min_spacing_px = 1e9, max_spacing_px = 0;
    double covered = 0;  // fraction of the target frame the corrected photo covers
    bool mapped = true;
  };

  // Every spacing between neighbouring grid nodes the photo shows, corrected by `camera`, and
  // the frame's coverage (the photo sampled every 2 px, marking 8 px cells of the target).
  Check check(const Camera& camera) const {
    Check out;
    const int n = 8;
    std::vector<std::vector<std::optional<Eigen::Vector2d>>> nodes(2 * n + 1);
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) {
        const Eigen::Vector2d p = photoFromScene(centre + spacing_px * Eigen::Vector2d(i, j));
        std::optional<Eigen::Vector2d> y;
        if (inPhoto(p)) {
          y = targetPixelFromSourcePixel(camera, p);
          if (!y) out.mapped = false;
        }
        nodes[static_cast<size_t>(i + n)].push_back(y);
      }
    const auto measure = [&](const std::optional<Eigen::Vector2d>& a,
                             const std::optional<Eigen::Vector2d>& b) {
      if (!a || !b) return;
      const double d = (*a - *b).norm();
      out.min_spacing_px = std::min(out.min_spacing_px, d);
      out.max_spacing_px = std::max(out.max_spacing_px, d);
      out.worst_ratio_error = std::max(out.worst_ratio_error, std::abs(d / spacing_px - 1));
    };
    for (size_t i = 0; i < nodes.size(); ++i)
      for (size_t j = 0; j < nodes[i].size(); ++j) {
        if (i + 1 < nodes.size()) measure(nodes[i][j], nodes[i + 1][j]);
        if (j + 1 < nodes[i].size()) measure(nodes[i][j], nodes[i][j + 1]);
      }
    const int cw = frame.width / 8, ch = frame.height / 8;
    std::vector<char> hit(static_cast<size_t>(cw * ch), 0);
    for (double y = 1; y < frame.height; y += 2)
      for (double x = 1; x < frame.width; x += 2) {
        const auto t = targetPixelFromSourcePixel(camera, {x, y});
        if (!t) continue;
        const int cx = static_cast<int>(std::floor(t->x() / 8));
        const int cy = static_cast<int>(std::floor(t->y() / 8));
        if (cx >= 0 && cy >= 0 && cx < cw && cy < ch) hit[static_cast<size_t>(cy * cw + cx)] = 1;
      }
    out.covered = static_cast<double>(std::count(hit.begin(), hit.end(), 1)) /
                  static_cast<double>(hit.size());
    return out;
  }
};

}  // namespace artcam::test
