// SPDX-License-Identifier: Apache-2.0
// Fixtures shared by the render tests, made in code: images, cameras from matrices, and a
// plain reference bilinear filter that does not use the renderer's sampler.
#pragma once

#include "core/model/camera.h"
#include "core/model/frames.h"
#include "core/model/image.h"
#include "core/model/structure.h"

#include <Eigen/Core>

#include <cmath>

namespace artcam::test {

// Smooth but textured linear RGB, values in (0, 1).
inline ImageF syntheticImage(int w, int h, int channels = 3) {
  ImageF img(w, h, channels, channels == 4 ? 3 : -1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const double alpha = channels == 4 ? 0.75 + 0.2 * std::sin(0.05 * x) : 1.0;
      p[0] = static_cast<float>(alpha * (0.5 + 0.4 * std::sin(0.31 * x + 0.17 * y)));
      if (channels > 1) p[1] = static_cast<float>(alpha * (0.5 + 0.4 * std::cos(0.13 * x - 0.29 * y)));
      if (channels > 2) p[2] = static_cast<float>(alpha * (0.3 + 0.002 * x + 0.001 * y));
      if (channels == 4) p[3] = static_cast<float>(alpha);
    }
  return img;
}

// A position camera from a homography given in the NORMALISED frames (column form).
inline Camera homographyCamera(const Eigen::Matrix3d& h_n, FrameSize source, FrameSize target) {
  Stage stage;
  for (const Eigen::MatrixXd& q : liftHomography(h_n)) stage.q.push_back(q);
  return Camera({Block{BlockKind::Position, 3}}, {stage}, source, target);
}

// Plain bilinear, pixel centres at i + 0.5, taps outside transparent; writes `channels` values
// and returns the coverage.
inline double referenceBilinear(const ImageF& img, double sx, double sy, float* out) {
  const double fx = sx - 0.5, fy = sy - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  double sum[4] = {0, 0, 0, 0}, cover = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double xi = x0 + dx, yi = y0 + dy;
      if (xi < 0 || yi < 0 || xi >= img.width || yi >= img.height) continue;
      const double w = (dx ? fx - x0 : 1 - (fx - x0)) * (dy ? fy - y0 : 1 - (fy - y0));
      const float* p = img.pixel(static_cast<int>(xi), static_cast<int>(yi));
      for (int c = 0; c < img.channels; ++c) sum[c] += w * p[c];
      cover += w;
    }
  for (int c = 0; c < img.channels; ++c) out[c] = static_cast<float>(sum[c]);
  return cover;
}

}  // namespace artcam::test
