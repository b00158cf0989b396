#include "core/effects/depth_of_field.h"

#include "core/render/parallel.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

namespace artcam {

Camera depthOfFieldCamera(const DepthOfFieldParams& p, FrameSize source, FrameSize target) {
  if (!(p.focus > 0.0) || !std::isfinite(p.focus))
    throw std::invalid_argument("depth of field: the focus depth must be positive");
  if (!(p.blur >= 0.0) || !std::isfinite(p.blur))
    throw std::invalid_argument("depth of field: blur must be a number ≥ 0");
  constexpr int kW = 2, kD = 7, kDh = 8, kN = 9;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  Stage stage;
  for (int i = 0; i < kD; ++i) stage.q.push_back(symmetricOuter(e(i), e(kW)));
  // σ² = k²(d − f)² / d²: numerator k²·(d, 1)ᵀ(d, 1) around f, denominator d².
  const double k2 = p.blur * p.blur;
  Eigen::MatrixXd num = Eigen::MatrixXd::Zero(kN, kN), den = Eigen::MatrixXd::Zero(kN, kN);
  num(kD, kD) = k2;
  num(kD, kDh) = num(kDh, kD) = -k2 * p.focus;
  num(kDh, kDh) = k2 * p.focus * p.focus;
  den(kD, kD) = 1.0;
  stage.q.push_back(num);
  stage.q.push_back(den);
  return Camera({Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4},
                 Block{BlockKind::Depth, 2}},
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

void checkInputs(const ImageF& rgba, const ImageF& sigma) {
  if (rgba.channels != 4 || rgba.empty())
    throw std::invalid_argument("depth of field needs a 4-channel premultiplied RGBA image");
  if (sigma.channels != 1 || sigma.width != rgba.width || sigma.height != rgba.height)
    throw std::invalid_argument("depth of field: the sigma image must be 1 channel of the "
                                "colour image's size");
}

ParallelOptions parallel(const BlurOptions& o, bool with_progress) {
  ParallelOptions po;
  po.threads = o.threads;
  if (with_progress) po.progress = o.progress;
  return po;
}

std::vector<float> gaussianKernel(double sigma, int& radius) {
  radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<float> g(static_cast<size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    const double v = std::exp(-0.5 * k * k / (sigma * sigma));
    g[static_cast<size_t>(k + radius)] = static_cast<float>(v);
    sum += v;
  }
  for (float& v : g) v = static_cast<float>(v / sum);
  return g;
}

// A 5-channel image (premultiplied rgba·mask, mask) without zero-filling it first.
struct Buffer5 {
  std::unique_ptr<float[]> data;
  int w = 0, h = 0;
  Buffer5(int width, int height)
      : data(new float[static_cast<size_t>(width) * static_cast<size_t>(height) * 5]), w(width), h(height) {}
  float* row(int y) const { return data.get() + static_cast<size_t>(y) * static_cast<size_t>(w) * 5; }
};

// Separable Gaussian of a 5-channel image, zero outside. The vertical pass runs over strips of
// columns so the 2r + 1 rows it reads stay in cache.
Buffer5 blur5(const Buffer5& in, double sigma, int threads) {
  const int w = in.w, h = in.h;
  int r = 0;
  const std::vector<float> g = gaussianKernel(sigma, r);
  Buffer5 tmp(w, h), out(w, h);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 32;
  parallelForRows(h, po, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float* src = in.row(y);
      float* dst = tmp.row(y);
      for (int x = 0; x < w; ++x) {
        float acc[5] = {0, 0, 0, 0, 0};
        const int k0 = std::max(-r, -x), k1 = std::min(r, w - 1 - x);
        for (int k = k0; k <= k1; ++k) {
          const float gk = g[static_cast<size_t>(k + r)];
          const float* p = src + static_cast<size_t>(x + k) * 5;
          for (int c = 0; c < 5; ++c) acc[c] += gk * p[c];
        }
        std::copy(acc, acc + 5, dst + static_cast<size_t>(x) * 5);
      }
    }
  });
  constexpr size_t kStrip = 1280;  // floats: 256 pixels of 5 channels
  const size_t row = static_cast<size_t>(w) * 5;
  parallelForRows(h, po, [&](int y0, int y1) {
    for (size_t c0 = 0; c0 < row; c0 += kStrip) {
      const size_t c1 = std::min(row, c0 + kStrip);
      for (int y = y0; y < y1; ++y) {
        float* dst = out.row(y);
        std::fill(dst + c0, dst + c1, 0.0f);
        const int k0 = std::max(-r, -y), k1 = std::min(r, h - 1 - y);
        for (int k = k0; k <= k1; ++k) {
          const float gk = g[static_cast<size_t>(k + r)];
          const float* src = tmp.row(y + k);
          for (size_t i = c0; i < c1; ++i) dst[i] += gk * src[i];
        }
      }
    }
  });
  return out;
}

// The halo-masked input of a level, f×f box-averaged (f = 1: as is; the last block may be
// partial: averaged over what it holds).
Buffer5 maskedShrunk(const ImageF& rgba, const ImageF& sigma, float threshold, int f, int threads) {
  const int w = rgba.width, h = rgba.height;
  Buffer5 out((w + f - 1) / f, (h + f - 1) / f);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(out.h, po, [&](int y0, int y1) {
    for (int sy = y0; sy < y1; ++sy) {
      float* dst = out.row(sy);
      std::fill(dst, dst + static_cast<size_t>(out.w) * 5, 0.0f);
      std::vector<float> count(static_cast<size_t>(out.w), 0.0f);
      for (int y = sy * f; y < std::min(h, sy * f + f); ++y)
        for (int x = 0; x < w; ++x) {
          const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
          const float m = sigma.data[i] >= threshold ? 1.0f : 0.0f;
          float* o = dst + static_cast<size_t>(x / f) * 5;
          for (int c = 0; c < 4; ++c) o[c] += m * rgba.data[i * 4 + static_cast<size_t>(c)];
          o[4] += m;
          count[static_cast<size_t>(x / f)] += 1.0f;
        }
      if (f > 1)
        for (int sx = 0; sx < out.w; ++sx)
          for (int c = 0; c < 5; ++c) dst[static_cast<size_t>(sx) * 5 + static_cast<size_t>(c)] /= count[static_cast<size_t>(sx)];
    }
  });
  return out;
}

// Bilinear read of a shrunk 5-channel image at full-resolution pixel (x, y).
void readShrunk(const Buffer5& b, int f, int x, int y, float* out) {
  const int sw = b.w, sh = b.h;
  const double fx = (x + 0.5) / f - 0.5, fy = (y + 0.5) / f - 0.5;
  const double cx = std::clamp(fx, 0.0, sw - 1.0), cy = std::clamp(fy, 0.0, sh - 1.0);
  const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
  const int x1 = std::min(x0 + 1, sw - 1), y1 = std::min(y0 + 1, sh - 1);
  const float tx = static_cast<float>(cx - x0), ty = static_cast<float>(cy - y0);
  const auto at = [&](int xx, int yy, int c) {
    return b.row(yy)[static_cast<size_t>(xx) * 5 + static_cast<size_t>(c)];
  };
  for (int c = 0; c < 5; ++c)
    out[c] = (1 - ty) * ((1 - tx) * at(x0, y0, c) + tx * at(x1, y0, c)) +
             ty * ((1 - tx) * at(x0, y1, c) + tx * at(x1, y1, c));
}

// One level of the stack: the halo-masked blur of σ, normalised by the blurred mask, written as
// 4 channels (a pixel the mask leaves empty falls back to its own colour).
std::vector<float> level(const ImageF& rgba, const ImageF& sigma, double s, const BlurOptions& o) {
  const int w = rgba.width, h = rgba.height;
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  const float threshold = static_cast<float>(o.halo_ratio * s);
  // Large σ: blur a box-shrunk copy (f ≤ σ/2) and read it back bilinearly; the box and the
  // tent add variance (f² − 1)/12 and f²/6, taken off the blur so the total matches σ².
  int f = 1;
  while (s / (2 * f) >= o.shrink_from_sigma / 2.0) f *= 2;
  const double extra = f > 1 ? (f * f - 1.0) / 12.0 + f * f / 6.0 : 0.0;
  const Buffer5 blurred = blur5(maskedShrunk(rgba, sigma, threshold, f, o.threads),
                                std::sqrt(std::max(s * s - extra, 0.25)) / f, o.threads);
  std::vector<float> out(n * 4);
  ParallelOptions po;
  po.threads = o.threads;
  po.band_rows = 64;
  parallelForRows(h, po, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
        float v[5];
        if (f == 1) std::copy(blurred.row(y) + static_cast<size_t>(x) * 5, blurred.row(y) + static_cast<size_t>(x) * 5 + 5, v);
        else readShrunk(blurred, f, x, y, v);
        const float* fallback = rgba.data.data() + i * 4;
        for (int c = 0; c < 4; ++c) out[i * 4 + static_cast<size_t>(c)] = v[4] > 1e-6f ? v[c] / v[4] : fallback[c];
      }
  });
  return out;
}

}  // namespace

ImageF exactBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options) {
  checkInputs(rgba, sigma_px);
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
            const double wt = g[static_cast<size_t>(std::abs(xx - x))] * g[static_cast<size_t>(std::abs(yy - y))];
            const float* p = rgba.pixel(xx, yy);
            for (int c = 0; c < 4; ++c) acc[c] += wt * p[c];
            weight += wt;
          }
        for (int c = 0; c < 4; ++c) o[c] = static_cast<float>(acc[c] / weight);
      }
  });
  return done ? out : ImageF{};
}

ImageF stackBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options) {
  checkInputs(rgba, sigma_px);
  if (!(options.level_ratio > 1.0)) throw std::invalid_argument("stack level ratio must exceed 1");
  const int w = rgba.width;
  ImageF out = rgba;  // sharp pixels stay as they are
  float max_sigma = 0.0f;
  for (float s : sigma_px.data) max_sigma = std::max(max_sigma, s);
  if (!(max_sigma >= options.min_sigma)) return out;
  // Level 0 is the sharp image (σ = 0); then σ_1 = min_sigma, σ_{L+1} = ratio·σ_L.
  std::vector<float> previous = rgba.data;
  double previous_sigma = 0.0;
  for (double s = std::max(options.min_sigma, options.first_level);; s *= options.level_ratio) {
    std::vector<float> current = level(rgba, sigma_px, s, options);
    const double lo2 = previous_sigma * previous_sigma, hi2 = s * s;
    ParallelOptions po;
    po.threads = options.threads;
    po.band_rows = 64;
    parallelForRows(rgba.height, po, [&](int y0, int y1) {
    for (size_t i = static_cast<size_t>(y0) * static_cast<size_t>(w); i < static_cast<size_t>(y1) * static_cast<size_t>(w); ++i) {
      const double si = sigma_px.data[i];
      if (!(si >= options.min_sigma) || si < previous_sigma || si >= s) {
        if (!(si >= s && s >= max_sigma)) continue;  // the last level takes what is left
      }
      // Blend weight matching the pixel's variance between the two levels.
      const double t = std::clamp((si * si - lo2) / (hi2 - lo2), 0.0, 1.0);
      for (int c = 0; c < 4; ++c)
        out.data[i * 4 + static_cast<size_t>(c)] = static_cast<float>(
            (1 - t) * previous[i * 4 + static_cast<size_t>(c)] + t * current[i * 4 + static_cast<size_t>(c)]);
    }
    });
    if (options.progress && !options.progress(std::min(1.0, s / max_sigma))) return {};
    if (s >= max_sigma) break;
    previous = std::move(current);
    previous_sigma = s;
  }
  return out;
}

}  // namespace artcam
