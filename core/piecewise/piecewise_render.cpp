// SPDX-License-Identifier: Apache-2.0
// Mesh warp through a piecewise camera; see piecewise_render.h.
#include "core/piecewise/piecewise_render.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {
namespace {

struct Vertex {
  Eigen::Vector2d source;  // source-camera pixels
  Eigen::Vector2d target;
  bool valid = false;
};

// Bilinear, pixel centres at i + 0.5, zero outside: the border fades to transparent.
void sampleBilinear(const ImageF& image, double x, double y, float* out, int channels) {
  const double fx = x - 0.5, fy = y - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  for (int c = 0; c < channels; ++c) out[c] = 0.0f;
  const double w[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
  const int xs[4] = {x0, x0 + 1, x0, x0 + 1}, ys[4] = {y0, y0, y0 + 1, y0 + 1};
  for (int k = 0; k < 4; ++k) {
    if (xs[k] < 0 || ys[k] < 0 || xs[k] >= image.width || ys[k] >= image.height || w[k] == 0.0)
      continue;
    const float* p = image.pixel(xs[k], ys[k]);
    const float wk = static_cast<float>(w[k]);
    if (image.alpha_channel >= 0) {
      for (int c = 0; c < image.channels; ++c) out[c] += wk * p[c];
    } else {
      for (int c = 0; c < image.channels; ++c) out[c] += wk * p[c];
      out[image.channels] += wk;  // coverage of an opaque source
    }
  }
}

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double px, double py) {
  return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

void rasterise(const Vertex& a, const Vertex& b, const Vertex& c, const ImageF& source,
               double source_scale_x, double source_scale_y, ImageF& out,
               PiecewiseRenderStats& stats) {
  const double area = edge(a.target, b.target, c.target.x(), c.target.y());
  if (!(std::abs(area) > 1e-12)) return;
  ++stats.triangles;
  const double lo_x = std::min({a.target.x(), b.target.x(), c.target.x()});
  const double hi_x = std::max({a.target.x(), b.target.x(), c.target.x()});
  const double lo_y = std::min({a.target.y(), b.target.y(), c.target.y()});
  const double hi_y = std::max({a.target.y(), b.target.y(), c.target.y()});
  const int x_begin = std::max(0, static_cast<int>(std::ceil(lo_x - 0.5)));
  const int x_end = std::min(out.width - 1, static_cast<int>(std::floor(hi_x - 0.5)));
  const int y_begin = std::max(0, static_cast<int>(std::ceil(lo_y - 0.5)));
  const int y_end = std::min(out.height - 1, static_cast<int>(std::floor(hi_y - 0.5)));
  // Shared edges are drawn by both triangles with the same interpolated value (the mesh is
  // continuous), so an inclusive test costs nothing but a second identical write.
  const double eps = -1e-9 * std::abs(area);
  for (int y = y_begin; y <= y_end; ++y)
    for (int x = x_begin; x <= x_end; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      double wa = edge(b.target, c.target, px, py) / area;
      double wb = edge(c.target, a.target, px, py) / area;
      double wc = edge(a.target, b.target, px, py) / area;
      if (wa < eps || wb < eps || wc < eps) continue;
      const Eigen::Vector2d s = wa * a.source + wb * b.source + wc * c.source;
      sampleBilinear(source, s.x() * source_scale_x, s.y() * source_scale_y, out.pixel(x, y),
                     source.channels);
      ++stats.covered_pixels;
    }
}

}  // namespace

ImageF renderPiecewise(const ImageF& source, const PiecewiseCamera& camera,
                       const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (source.empty()) throw std::invalid_argument("renderPiecewise: empty source image");
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("renderPiecewise: the camera has no image frames");
  const int channels = source.alpha_channel >= 0 ? source.channels : source.channels + 1;
  const FrameSize size = options.output.isImage() ? options.output : camera.target_size;
  const double out_x = static_cast<double>(size.width) / camera.target_size.width;
  const double out_y = static_cast<double>(size.height) / camera.target_size.height;
  ImageF out(size.width, size.height, channels, channels - 1);
  PiecewiseRenderStats stats;
  if (camera.patches.empty()) {
    if (stats_out) *stats_out = stats;
    return out;
  }
  const double step = std::max(0.25, options.mesh_step_px);

  PatchRect all = camera.patches.front().rect;
  for (const CameraPatch& p : camera.patches) {
    all.x0 = std::min(all.x0, p.rect.x0);
    all.y0 = std::min(all.y0, p.rect.y0);
    all.x1 = std::max(all.x1, p.rect.x1);
    all.y1 = std::max(all.y1, p.rect.y1);
  }
  const int nx = static_cast<int>(std::ceil(all.width() / step)) + 1;
  const int ny = static_cast<int>(std::ceil(all.height() / step)) + 1;
  std::vector<Vertex> lattice(static_cast<size_t>(nx) * static_cast<size_t>(ny));
  const double tolerance = 1e-9 * std::max(all.width(), all.height());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Vertex& v = lattice[static_cast<size_t>(j) * static_cast<size_t>(nx) + static_cast<size_t>(i)];
      v.source = {std::min(all.x1, all.x0 + i * step), std::min(all.y1, all.y0 + j * step)};
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int count = 0;
      for (size_t k = 0; k < camera.patches.size(); ++k) {
        const CameraPatch& p = camera.patches[k];
        if (p.rect.contains(v.source, tolerance) && camera.supports(static_cast<int>(k), v.source))
          if (const auto y = targetPixelFromSourcePixel(p.camera, v.source)) {
            sum += *y;
            ++count;
          }
      }
      v.valid = count > 0;
      if (v.valid) v.target = (sum / count).cwiseProduct(Eigen::Vector2d(out_x, out_y));
    }

  const double sx = static_cast<double>(source.width) / camera.source_size.width;
  const double sy = static_cast<double>(source.height) / camera.source_size.height;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const auto at = [&](int di, int dj) -> const Vertex& {
        return lattice[static_cast<size_t>(j + dj) * static_cast<size_t>(nx) +
                       static_cast<size_t>(i + di)];
      };
      const Vertex &v00 = at(0, 0), &v10 = at(1, 0), &v01 = at(0, 1), &v11 = at(1, 1);
      // A cell counts only when its centre lies where a patch has data (the quadtree's empty
      // corners stay empty).
      const Eigen::Vector2d centre = 0.25 * (v00.source + v10.source + v01.source + v11.source);
      if (!camera.targetPixelFromSourcePixel(centre)) continue;
      if (v00.valid && v10.valid && v11.valid) rasterise(v00, v10, v11, source, sx, sy, out, stats);
      if (v00.valid && v11.valid && v01.valid) rasterise(v00, v11, v01, source, sx, sy, out, stats);
    }
  if (stats_out) *stats_out = stats;
  return out;
}

void compositeOver(const ImageF& top, ImageF& bottom) {
  if (top.width != bottom.width || top.height != bottom.height || top.alpha_channel < 0)
    throw std::invalid_argument("compositeOver: sizes differ or the top image has no alpha");
  const int colour = top.channels - 1;
  const size_t n = static_cast<size_t>(top.width) * static_cast<size_t>(top.height);
  for (size_t k = 0; k < n; ++k) {
    const float* t = top.data.data() + k * static_cast<size_t>(top.channels);
    float* b = bottom.data.data() + k * static_cast<size_t>(bottom.channels);
    const float keep = 1.0f - std::clamp(t[top.alpha_channel], 0.0f, 1.0f);
    for (int c = 0; c < bottom.channels; ++c) {
      if (c == bottom.alpha_channel) {
        b[c] = t[top.alpha_channel] + keep * b[c];
      } else {
        const int tc = std::min(c, colour - 1);  // grey graphics over colour photos
        b[c] = t[tc] + keep * b[c];
      }
    }
  }
}

}  // namespace artcam
