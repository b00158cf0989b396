// SPDX-License-Identifier: Apache-2.0
// Mesh warp through a piecewise camera; see piecewise_render.h.
#include "core/piecewise/piecewise_render.h"

#include "core/model/image_view.h"
#include "core/render/rational_map.h"
#include "core/render/span_sampler.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

struct Vertex {
  Eigen::Vector2d source;  // source-camera pixels
  Eigen::Vector2d target;
  bool valid = false;
};

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double px, double py) {
  return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

// One mapped triangle: its output rows, and what a pixel centre inside needs: the three edge
// functions and the source position, each affine in (x, y), so a row costs adds.
struct Triangle {
  Eigen::Vector2d a, b, c;        // output pixels
  Eigen::Vector2d sa, sb, sc;     // source pixels of the source image
  double area = 0.0;
  int y_begin = 0, y_end = -1;    // output rows with a pixel centre inside the bounding box
};

constexpr int kBandRows = 16;

struct Mesh {
  std::vector<Triangle> triangles;
  std::vector<std::vector<int>> bands;  // triangles touching each band of kBandRows output rows
};

Mesh buildMesh(const PiecewiseCamera& camera, FrameSize source_image, FrameSize size, double step,
               int threads) {
  const double out_x = static_cast<double>(size.width) / camera.target_size.width;
  const double out_y = static_cast<double>(size.height) / camera.target_size.height;
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
  std::vector<unsigned char> cell_ok(static_cast<size_t>(nx) * static_cast<size_t>(ny), 0);
  const double tolerance = 1e-9 * std::max(all.width(), all.height());
  // Each patch's forward map in pixels, evaluated from its six coefficients per form
  // (rational_map.h): the lattice asks it ~1.5 million times at 24 MP.
  std::vector<RationalMap> maps;
  for (const CameraPatch& p : camera.patches) maps.emplace_back(p.camera, camera.source_size, camera.target_size);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(ny, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < nx; ++i) {
        Vertex& v = lattice[static_cast<size_t>(j) * static_cast<size_t>(nx) + static_cast<size_t>(i)];
        v.source = {std::min(all.x1, all.x0 + i * step), std::min(all.y1, all.y0 + j * step)};
        Eigen::Vector2d sum = Eigen::Vector2d::Zero();
        int count = 0;
        for (size_t k = 0; k < camera.patches.size(); ++k) {
          const CameraPatch& p = camera.patches[k];
          Eigen::Vector2d y;
          if (p.rect.contains(v.source, tolerance) && camera.supports(static_cast<int>(k), v.source) &&
              maps[k].evaluate(v.source, y, nullptr)) {
            sum += y;
            ++count;
          }
        }
        v.valid = count > 0;
        if (v.valid) v.target = (sum / count).cwiseProduct(Eigen::Vector2d(out_x, out_y));
        // A cell counts only when its centre lies where a patch has data (the quadtree's
        // empty corners stay empty).
        if (i + 1 < nx && j + 1 < ny) {
          const Eigen::Vector2d centre(std::min(all.x1, all.x0 + (i + 0.5) * step),
                                       std::min(all.y1, all.y0 + (j + 0.5) * step));
          bool inside = false;
          for (size_t k = 0; k < camera.patches.size() && !inside; ++k)
            inside = camera.patches[k].rect.contains(centre) && camera.supports(static_cast<int>(k), centre);
          cell_ok[static_cast<size_t>(j) * static_cast<size_t>(nx) + static_cast<size_t>(i)] = inside ? 1 : 0;
        }
      }
  });
  const double sx = static_cast<double>(source_image.width) / camera.source_size.width;
  const double sy = static_cast<double>(source_image.height) / camera.source_size.height;
  Mesh mesh;
  mesh.bands.resize(static_cast<size_t>((size.height + kBandRows - 1) / kBandRows));
  const auto add = [&](const Vertex& a, const Vertex& b, const Vertex& c) {
    Triangle t;
    t.a = a.target, t.b = b.target, t.c = c.target;
    t.area = edge(t.a, t.b, t.c.x(), t.c.y());
    if (!(std::abs(t.area) > 1e-12)) return;
    const auto scaled = [&](const Eigen::Vector2d& s) { return Eigen::Vector2d(s.x() * sx, s.y() * sy); };
    t.sa = scaled(a.source), t.sb = scaled(b.source), t.sc = scaled(c.source);
    const double lo_y = std::min({t.a.y(), t.b.y(), t.c.y()}), hi_y = std::max({t.a.y(), t.b.y(), t.c.y()});
    t.y_begin = std::max(0, static_cast<int>(std::ceil(lo_y - 0.5)));
    t.y_end = std::min(size.height - 1, static_cast<int>(std::floor(hi_y - 0.5)));
    const double lo_x = std::min({t.a.x(), t.b.x(), t.c.x()}), hi_x = std::max({t.a.x(), t.b.x(), t.c.x()});
    if (t.y_begin > t.y_end || hi_x < 0.5 - 1e-9 || lo_x > size.width - 0.5 + 1e-9) {
      mesh.triangles.push_back(t);  // counted, never drawn
      return;
    }
    const int index = static_cast<int>(mesh.triangles.size());
    mesh.triangles.push_back(t);
    for (int band = t.y_begin / kBandRows; band <= t.y_end / kBandRows; ++band)
      mesh.bands[static_cast<size_t>(band)].push_back(index);
  };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      if (!cell_ok[static_cast<size_t>(j) * static_cast<size_t>(nx) + static_cast<size_t>(i)]) continue;
      const auto at = [&](int di, int dj) -> const Vertex& {
        return lattice[static_cast<size_t>(j + dj) * static_cast<size_t>(nx) + static_cast<size_t>(i + di)];
      };
      const Vertex &v00 = at(0, 0), &v10 = at(1, 0), &v01 = at(0, 1), &v11 = at(1, 1);
      if (v00.valid && v10.valid && v11.valid) add(v00, v10, v11);
      if (v00.valid && v11.valid && v01.valid) add(v00, v11, v01);
    }
  return mesh;
}

// The triangle's pixel centres in rows [y0, y1) into the band's position buffers (row r of
// the band at r · width). Shared edges are drawn by both triangles with the same value (the
// mesh is continuous), so the inclusive test costs nothing but a second identical write.
long long rasterise(const Triangle& t, int y0, int y1, int width, float* sx, float* sy,
                    unsigned char* valid, int band_y0) {
  const double lo_x = std::min({t.a.x(), t.b.x(), t.c.x()}), hi_x = std::max({t.a.x(), t.b.x(), t.c.x()});
  const int x_begin = std::max(0, static_cast<int>(std::ceil(lo_x - 0.5)));
  const int x_end = std::min(width - 1, static_cast<int>(std::floor(hi_x - 0.5)));
  const double eps = -1e-9 * std::abs(t.area);
  const double inv = 1.0 / t.area;
  // Each barycentric weight is affine in x along a row: w(x) = w(x_begin) + (x − x_begin) dw.
  const double dwa = -(t.c.y() - t.b.y()) * inv, dwb = -(t.a.y() - t.c.y()) * inv, dwc = -(t.b.y() - t.a.y()) * inv;
  long long covered = 0;
  for (int y = std::max(y0, t.y_begin); y <= std::min(y1 - 1, t.y_end); ++y) {
    const double py = y + 0.5, px0 = x_begin + 0.5;
    const double wa0 = edge(t.b, t.c, px0, py) * inv, wb0 = edge(t.c, t.a, px0, py) * inv,
                 wc0 = edge(t.a, t.b, px0, py) * inv;
    const size_t row = static_cast<size_t>(y - band_y0) * static_cast<size_t>(width);
    for (int x = x_begin; x <= x_end; ++x) {
      const double k = x - x_begin;
      const double wa = wa0 + k * dwa, wb = wb0 + k * dwb, wc = wc0 + k * dwc;
      if (wa < eps || wb < eps || wc < eps) continue;
      const Eigen::Vector2d s = wa * t.sa + wb * t.sb + wc * t.sc;
      sx[row + static_cast<size_t>(x)] = static_cast<float>(s.x());
      sy[row + static_cast<size_t>(x)] = static_cast<float>(s.y());
      valid[row + static_cast<size_t>(x)] = 1;
      ++covered;
    }
  }
  return covered;
}

}  // namespace

void renderPiecewise(const ConstImageView& source, const PiecewiseCamera& camera, const ImageView& out,
                     const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (source.empty()) throw std::invalid_argument("renderPiecewise: empty source image");
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("renderPiecewise: the camera has no image frames");
  const SpanSampler sampler(source, out, options.filter, options.allow_simd);  // validates both
  const FrameSize size{out.width, out.height};
  PiecewiseRenderStats stats;
  for (int y = 0; y < out.height; ++y)
    std::memset(out.row(y), 0, static_cast<size_t>(out.width) * static_cast<size_t>(out.pixelBytes()));
  if (camera.patches.empty()) {
    if (stats_out) *stats_out = stats;
    return;
  }
  const Mesh mesh = buildMesh(camera, {source.width, source.height}, size,
                              std::max(0.25, options.mesh_step_px), options.threads);
  stats.triangles = static_cast<int>(mesh.triangles.size());
  std::atomic<long long> covered{0};
  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = kBandRows;
  parallelForRows(out.height, po, [&](int y0, int y1) {
    const size_t cells = static_cast<size_t>(kBandRows) * static_cast<size_t>(out.width);
    std::vector<float> sx(cells), sy(cells);
    std::vector<unsigned char> valid(cells, 0);
    long long band_covered = 0;
    for (const int index : mesh.bands[static_cast<size_t>(y0 / kBandRows)])
      band_covered += rasterise(mesh.triangles[static_cast<size_t>(index)], y0, y1, out.width, sx.data(),
                                sy.data(), valid.data(), y0);
    for (int y = y0; y < y1; ++y) {
      const size_t row = static_cast<size_t>(y - y0) * static_cast<size_t>(out.width);
      for (int x0 = 0; x0 < out.width; x0 += 64) {
        const int n = std::min(64, out.width - x0);
        sampler.run(y, x0, n, sx.data() + row + x0, sy.data() + row + x0, valid.data() + row + x0);
      }
    }
    covered += band_covered;
  });
  stats.covered_pixels = covered.load();
  if (stats_out) *stats_out = stats;
}

ImageF renderPiecewise(const ImageF& source, const PiecewiseCamera& camera,
                       const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (source.empty()) throw std::invalid_argument("renderPiecewise: empty source image");
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("renderPiecewise: the camera has no image frames");
  const int channels = source.alpha_channel >= 0 ? source.channels : source.channels + 1;
  const FrameSize size = options.output.isImage() ? options.output : camera.target_size;
  ImageF out(size.width, size.height, channels, channels - 1);
  renderPiecewise(viewOf(source), camera, viewOf(out), options, stats_out);
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
