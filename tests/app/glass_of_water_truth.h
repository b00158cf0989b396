// SPDX-License-Identifier: Apache-2.0
// The truth for Fig 8 whole (`artcam sample glass-of-water`, 320 × 240): where the ray tracer
// sees the backdrop through the water or the air, a graphic inserted there must show the
// graphic sampled at the traced backdrop point, over the photo, in premultiplied alpha. Made
// from the tracer (core/piecewise/sample_scenes.h) and the files alone, for the command line's
// chained inserts and the studio's insertion media alike.
#pragma once

#include "core/model/image.h"
#include "core/piecewise/sample_scenes.h"

#include <algorithm>
#include <cmath>

namespace artcam::test {

// The scene `artcam sample glass-of-water --size 320x240` traces (cmd_sample.cpp).
inline GlassOfWaterScene sampleGlassOfWater320() {
  GlassOfWaterScene scene;
  scene.focal_px = 0.9 * 320;
  scene.backdrop_half = 0.75;
  scene.photo_width = 320;
  scene.photo_height = 240;
  return scene;
}

struct TracerComparison {
  double mean = 1.0;    // mean |result − truth| per channel, linear
  double change = 0.0;  // mean |truth − photo|: what the graphic changes
  long long pixels = 0;
};

// Over the interior of the medium's region (4 px from its edge, where the grid's matches bound
// the patches), linear light: `photo`, `graphic` and `result` as read from the files.
inline TracerComparison compareWithTracer(const ImageF& photo, const ImageF& graphic,
                                          const ImageF& result, GlassOfWaterScene scene,
                                          GlassOfWaterScene::Medium medium) {
  scene.medium = medium;
  const auto bilinear = [&](const Eigen::Vector2d& g, int c) {
    const double fx = std::clamp(g.x() - 0.5, 0.0, graphic.width - 1.001);
    const double fy = std::clamp(g.y() - 0.5, 0.0, graphic.height - 1.001);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const double tx = fx - x0, ty = fy - y0;
    return (1 - ty) * ((1 - tx) * graphic.pixel(x0, y0)[c] + tx * graphic.pixel(x0 + 1, y0)[c]) +
           ty * ((1 - tx) * graphic.pixel(x0, y0 + 1)[c] + tx * graphic.pixel(x0 + 1, y0 + 1)[c]);
  };
  double sum = 0.0, moved = 0.0;
  long long n = 0;
  constexpr int kIn = 4;
  for (int y = kIn; y + kIn < photo.height; ++y)
    for (int x = kIn; x + kIn < photo.width; ++x) {
      bool interior = true;
      for (int dy = -kIn; dy <= kIn && interior; dy += kIn)
        for (int dx = -kIn; dx <= kIn && interior; dx += kIn)
          interior = scene.graphicFromPhoto({x + dx + 0.5, y + dy + 0.5}).has_value();
      if (!interior) continue;
      const Eigen::Vector2d g = *scene.graphicFromPhoto({x + 0.5, y + 0.5});
      const double alpha = bilinear(g, 3);
      for (int c = 0; c < 3; ++c) {
        const double truth = bilinear(g, c) + (1.0 - alpha) * photo.pixel(x, y)[c];
        sum += std::abs(result.pixel(x, y)[c] - truth);
        moved += std::abs(truth - photo.pixel(x, y)[c]);
      }
      ++n;
    }
  TracerComparison out;
  out.pixels = n;
  if (n > 0) {
    out.mean = sum / (3.0 * n);
    out.change = moved / (3.0 * n);
  }
  return out;
}

}  // namespace artcam::test
