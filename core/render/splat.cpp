// SPDX-License-Identifier: Apache-2.0
// The forward mesh splat (splat.h).
#include "core/render/splat.h"

#include "core/model/frames.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace artcam {

namespace {

// One mapped source point: where it lands (output pixels) and what it carries there.
struct Vertex {
  float x = 0, y = 0;
  float rgba[4] = {0, 0, 0, 0};
  float depth = 0;
  signed char side = 0;  // sign of q_h; 0: no valid position
};

// Per output pixel: sums over the covering sub-samples.
struct Accumulator {
  std::vector<float> sum;  // rgba + depth, 5 per pixel
  std::vector<int> count;
  int width = 0, height = 0;
};

// Edge function: twice the signed area of (a, b, p).
inline double edge(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Top-left fill rule for a counter-clockwise triangle in y-down sample coordinates, so a
// sub-sample on an edge shared by two triangles counts once.
inline bool topLeft(double ax, double ay, double bx, double by) {
  return (ay == by && bx < ax) || by > ay;
}

// One triangle onto the sample grid of G samples per output pixel side, sample (i, j) at output
// point ((i + 0.5)/G, (j + 0.5)/G), each sample adding `weight`.
void rasteriseOnGrid(const Vertex* v[3], int g, int weight, Accumulator& acc) {
  double px[3], py[3];
  for (int k = 0; k < 3; ++k) {
    px[k] = v[k]->x * g - 0.5;  // sample units: sample (i, j) sits at (i, j)
    py[k] = v[k]->y * g - 0.5;
  }
  double area = edge(px[0], py[0], px[1], py[1], px[2], py[2]);
  if (area < 0) {  // a folded triangle still covers: orient it counter-clockwise
    std::swap(px[1], px[2]);
    std::swap(py[1], py[2]);
    std::swap(v[1], v[2]);
    area = -area;
  }
  const int w = acc.width * g, h = acc.height * g;
  const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({px[0], px[1], px[2]}))));
  const int i1 = std::min(w - 1, static_cast<int>(std::floor(std::max({px[0], px[1], px[2]}))));
  const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({py[0], py[1], py[2]}))));
  const int j1 = std::min(h - 1, static_cast<int>(std::floor(std::max({py[0], py[1], py[2]}))));
  if (i0 > i1 || j0 > j1) return;
  const bool tl[3] = {topLeft(px[1], py[1], px[2], py[2]), topLeft(px[2], py[2], px[0], py[0]),
                      topLeft(px[0], py[0], px[1], py[1])};
  const double inv = 1.0 / area;
  const float fw = static_cast<float>(weight);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double e[3] = {edge(px[1], py[1], px[2], py[2], i, j),
                           edge(px[2], py[2], px[0], py[0], i, j),
                           edge(px[0], py[0], px[1], py[1], i, j)};
      bool inside = true;
      for (int k = 0; k < 3; ++k) inside = inside && (e[k] > 0 || (e[k] == 0 && tl[k]));
      if (!inside) continue;
      const size_t pixel = static_cast<size_t>(j / g) * static_cast<size_t>(acc.width) +
                           static_cast<size_t>(i / g);
      float* sum = acc.sum.data() + 5 * pixel;
      // Barycentric weights: e[k] is the area opposite vertex k.
      const double b0 = e[0] * inv, b1 = e[1] * inv, b2 = 1.0 - b0 - b1;
      for (int k = 0; k < 4; ++k)
        sum[k] += fw * static_cast<float>(b0 * v[0]->rgba[k] + b1 * v[1]->rgba[k] + b2 * v[2]->rgba[k]);
      sum[4] += fw * static_cast<float>(b0 * v[0]->depth + b1 * v[1]->depth + b2 * v[2]->depth);
      acc.count[pixel] += weight;
    }
}

void rasterise(const Vertex& a, const Vertex& b, const Vertex& c, int s, Accumulator& acc,
               long long& dropped) {
  if (!a.side || a.side != b.side || a.side != c.side) {
    ++dropped;
    return;
  }
  const Vertex* v[3] = {&a, &b, &c};
  const double area_px = 0.5 * std::abs(edge(a.x, a.y, b.x, b.y, c.x, c.y));
  if (!(area_px > 1e-12)) return;  // degenerate (or NaN): covers nothing
  // A triangle of at least a quarter output pixel (its quad ≥ 0.5 px²: magnified, about 1:1 or
  // mildly minified)
  // is point-sampled at pixel centres with the weight of S² sub-samples: the piecewise-linear
  // interpolant read exactly there, with no extra box blur (an identity map returns the
  // source). Smaller ones are minified: S×S sub-samples average them (no moiré).
  if (area_px >= 0.25) rasteriseOnGrid(v, 1, s * s, acc);
  else rasteriseOnGrid(v, s, 1, acc);
}

}  // namespace

AttributedImage splatImage(const ImageF& rgba, const ImageF* depth, const Camera& camera,
                           FrameSize out_px, const SplatOptions& options, SplatSummary* summary) {
  SplatSummary local;
  SplatSummary& report = summary ? *summary : local;
  report = SplatSummary{};
  if (rgba.channels != 4 || rgba.alpha_channel != 3 || rgba.empty())
    throw std::invalid_argument("splatImage needs a premultiplied RGBA source (rgbaFromImage)");
  if (options.supersample < 1 || options.supersample > 8)
    throw std::invalid_argument("splat supersampling must be 1..8 sub-samples per side");
  if (!out_px.isImage()) throw std::invalid_argument("splat output size must be positive");
  const AttributeEvaluator eval(camera);
  if (eval.readsDepth() && (!depth || depth->empty()))
    throw std::invalid_argument("this camera reads depth: give a depth image");

  const FrameSize source_px{rgba.width, rgba.height};
  const int s = options.supersample;
  Accumulator acc;
  acc.width = out_px.width;
  acc.height = out_px.height;
  acc.sum.assign(static_cast<size_t>(out_px.width) * static_cast<size_t>(out_px.height) * 5, 0.0f);
  acc.count.assign(static_cast<size_t>(out_px.width) * static_cast<size_t>(out_px.height), 0);

  // Vertex columns -1..w, rows -1..h: the ring outside carries transparent colour.
  const int vw = rgba.width + 2;
  const auto mapRow = [&](int j, std::vector<Vertex>& row) {
    row.resize(static_cast<size_t>(vw));
    AttributeEvaluator::Output o;
    const int sj = std::clamp(j, 0, rgba.height - 1);
    for (int i = -1; i <= rgba.width; ++i) {
      const int si = std::clamp(i, 0, rgba.width - 1);
      const bool outside = si != i || sj != j;
      const Eigen::Vector2d n = normalizedFromPixel(source_px, {i + 0.5, j + 0.5});
      const double d = depth ? sampleDepth(*depth, source_px, si + 0.5, sj + 0.5) : 0.0;
      eval.evaluate(n.x(), n.y(), rgba.pixel(si, sj), d, o);
      Vertex& v = row[static_cast<size_t>(i + 1)];
      v = Vertex{};
      if (!o.position_valid) continue;
      const Eigen::Vector2d t = pixelFromNormalized(out_px, {o.position[0], o.position[1]});
      v.x = static_cast<float>(t.x());
      v.y = static_cast<float>(t.y());
      if (!std::isfinite(v.x) || !std::isfinite(v.y)) continue;
      v.side = o.position_weight > 0 ? 1 : -1;
      v.depth = o.depth;
      if (!outside && o.attributes_valid) std::copy(o.rgba, o.rgba + 4, v.rgba);
    }
  };

  // Bands of source rows: their vertex rows mapped in parallel, then rasterised in order.
  constexpr int kBand = 32;
  std::vector<std::vector<Vertex>> rows;
  std::vector<Vertex> carry;  // the last vertex row of the previous band
  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = 4;
  for (int j0 = -1; j0 < rgba.height; j0 += kBand) {
    const int j1 = std::min(rgba.height, j0 + kBand);  // vertex rows j0..j1 inclusive
    const int first = carry.empty() ? j0 : j0 + 1;
    rows.assign(static_cast<size_t>(j1 - j0 + 1), {});
    if (!carry.empty()) rows[0] = std::move(carry);
    parallelForRows(j1 - first + 1, po, [&](int r0, int r1) {
      for (int r = r0; r < r1; ++r) mapRow(first + r, rows[static_cast<size_t>(first + r - j0)]);
    });
    for (int j = j0; j < j1; ++j) {
      const std::vector<Vertex>& top = rows[static_cast<size_t>(j - j0)];
      const std::vector<Vertex>& bottom = rows[static_cast<size_t>(j - j0 + 1)];
      for (int i = 0; i + 1 < vw; ++i) {
        const Vertex& v00 = top[static_cast<size_t>(i)];
        const Vertex& v10 = top[static_cast<size_t>(i + 1)];
        const Vertex& v01 = bottom[static_cast<size_t>(i)];
        const Vertex& v11 = bottom[static_cast<size_t>(i + 1)];
        rasterise(v00, v10, v11, s, acc, report.dropped_triangles);
        rasterise(v00, v11, v01, s, acc, report.dropped_triangles);
      }
    }
    carry = std::move(rows.back());
    if (options.progress && !options.progress(static_cast<double>(j1 + 1) / (rgba.height + 1))) {
      report.cancelled = true;
      return {};
    }
  }

  AttributedImage out;
  out.colour = ImageF(out_px.width, out_px.height, 4, 3);
  if (eval.readsDepth()) out.depth = ImageF(out_px.width, out_px.height, 1);
  const float full = static_cast<float>(s * s);
  for (size_t p = 0; p < acc.count.size(); ++p) {
    const int n = acc.count[p];
    float* c = out.colour.data.data() + 4 * p;
    if (n == 0) {
      ++report.transparent_pixels;
      continue;
    }
    // C / max(n, S²): partial coverage lowers alpha, folds average (splat.h).
    const float norm = 1.0f / std::max(static_cast<float>(n), full);
    for (int k = 0; k < 4; ++k) c[k] = acc.sum[5 * p + static_cast<size_t>(k)] * norm;
    c[3] = std::clamp(c[3], 0.0f, 1.0f);
    if (!(c[3] > 0.0f)) {
      std::fill(c, c + 4, 0.0f);
      ++report.transparent_pixels;
    }
    if (!out.depth.empty()) out.depth.data[p] = acc.sum[5 * p + 4] / static_cast<float>(n);
  }
  return out;
}

}  // namespace artcam
