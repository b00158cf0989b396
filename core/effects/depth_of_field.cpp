// SPDX-License-Identifier: Apache-2.0
#include "core/effects/depth_of_field.h"

#include "core/effects/blur_inputs.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace artcam {

Camera depthOfFieldCamera(const DepthOfFieldParams& p, FrameSize source, FrameSize target) {
  if (!(p.focus >= 0.0) || !std::isfinite(p.focus))
    throw std::invalid_argument("depth of field: the focus depth must be ≥ 0");
  if (!(p.blur >= 0.0) || !std::isfinite(p.blur))
    throw std::invalid_argument("depth of field: blur must be a number ≥ 0");
  if (!(p.thin_lens >= 0.0 && p.thin_lens <= 1.0))
    throw std::invalid_argument("depth of field: thin-lens must be between 0 (linear) and 1");
  if (p.focus == 0.0 && p.thin_lens != 0.0)
    throw std::invalid_argument(
        "depth of field: focus 0 (blur proportional to depth) needs thin-lens 0; a thin lens "
        "focused at depth 0 blurs everything alike");
  constexpr int kW = 2, kD = 7, kDh = 8, kN = 9;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  Stage stage;
  for (int i = 0; i < kD; ++i) stage.q.push_back(symmetricOuter(e(i), e(kW)));
  // σ² = k²(d − f)² / ((1 − γ)f + γd)²: numerator k²·(d − f·d_h)², denominator the square of
  // the linear form γ·d + (1 − γ)·f·d_h (header; the paper's eqs (1)/(5) on the depth block).
  const double k2 = p.blur * p.blur, g = p.thin_lens, fh = (1.0 - g) * p.focus;
  Eigen::MatrixXd num = Eigen::MatrixXd::Zero(kN, kN), den = Eigen::MatrixXd::Zero(kN, kN);
  num(kD, kD) = k2;
  num(kD, kDh) = num(kDh, kD) = -k2 * p.focus;
  num(kDh, kDh) = k2 * p.focus * p.focus;
  den(kD, kD) = g * g;
  den(kD, kDh) = den(kDh, kD) = g * fh;
  den(kDh, kDh) = fh * fh;
  // Focus 0 (γ = 0): σ = k·d, the paper's blur proportional to depth; the denominator is d_h².
  if (p.focus == 0.0) den(kDh, kDh) = 1.0;
  stage.q.push_back(num);
  stage.q.push_back(den);
  return Camera(
      {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}, Block{BlockKind::Depth, 2}},
      {stage}, source, target);
}

ImageF sigmaPixelsFromVariance(const ImageF& variance, double max_sigma_px) {
  ImageF sigma(variance.width, variance.height, 1);
  const double scale = std::max(variance.width, variance.height) / 2.0;
  for (size_t i = 0; i < sigma.data.size(); ++i) {
    const double v = variance.data[i * static_cast<size_t>(variance.channels)];
    const double s = v > 0.0 && std::isfinite(v) ? std::sqrt(v) * scale : 0.0;
    sigma.data[i] = static_cast<float>(std::min(s, max_sigma_px));
  }
  return sigma;
}

namespace {

ParallelOptions parallel(const BlurOptions& o, bool with_progress) {
  ParallelOptions po;
  po.threads = o.threads;
  if (with_progress) po.progress = o.progress;
  return po;
}

}  // namespace

ImageF exactBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options) {
  checkBlurInputs(rgba, sigma_px);
  const int w = rgba.width, h = rgba.height;
  ImageF out(w, h, 4, 3);
  const bool done = parallelForRows(h, parallel(options, true), [&](int y0, int y1) {
    std::vector<double> g;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const double s = sigma_px.pixel(x, y)[0];
        float* o = out.pixel(x, y);
        if (!(s >= options.min_sigma)) {
          std::copy(rgba.pixel(x, y), rgba.pixel(x, y) + 4, o);
          continue;
        }
        const int r = static_cast<int>(std::ceil(3.0 * s));
        g.resize(static_cast<size_t>(r + 1));
        for (int k = 0; k <= r; ++k) g[static_cast<size_t>(k)] = std::exp(-0.5 * k * k / (s * s));
        const double threshold = options.halo_ratio * s;
        double acc[4] = {0, 0, 0, 0}, weight = 0.0;
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
            if (!(sigma_px.pixel(xx, yy)[0] >= threshold)) continue;  // the halo rule
            const double wt =
                g[static_cast<size_t>(std::abs(xx - x))] * g[static_cast<size_t>(std::abs(yy - y))];
            const float* p = rgba.pixel(xx, yy);
            for (int c = 0; c < 4; ++c) acc[c] += wt * p[c];
            weight += wt;
          }
        for (int c = 0; c < 4; ++c) o[c] = static_cast<float>(acc[c] / weight);
      }
  });
  return done ? out : ImageF{};
}

}  // namespace artcam
