// SPDX-License-Identifier: Apache-2.0
// The forward mesh splat (splat.h).
#include "core/render/splat.h"

#include "core/model/frames.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace artcam {

namespace {

// The sample lattice: 2S steps per output pixel, so pixel i's centre is lattice point 2S·i + S
// and its sub-sample k is 2S·i + 2k + 1. Vertices are snapped to 1/256 of a step and the edge
// functions are exact integers: two triangles that share an edge agree on every sample of it,
// whatever their size class (watertight by arithmetic, not by luck).
constexpr int kFixedBits = 8;
constexpr std::int64_t kFixedOne = std::int64_t{1} << kFixedBits;
// |coordinate| bound in fixed units that keeps every edge-function product inside int64.
constexpr std::int64_t kFixedLimit = std::int64_t{1} << 29;

// Front-ness of a sample (splat.h, folds): larger is in front. Samples of torn triangles are
// behind every sample of the intact mesh.
constexpr float kTornKey = -1e30f;
constexpr float kKeyTolerance = 0.05f;  // ln units: keys within 5 % are one layer

// One mapped source point: where it lands (output pixels) and what it carries there.
struct Vertex {
  std::int64_t fx = 0, fy = 0;       // output position on the lattice, fixed point
  float out[5] = {0, 0, 0, 0, 0};    // output rgba (premultiplied) and depth
  float read[5] = {0, 0, 0, 0, 0};   // input rgba (premultiplied) and depth: what the geometry reads
  float key = 0;                     // −ln(input depth) where the geometry reads depth
  signed char side = 0;              // sign of q_h; 0: no valid position (or beyond the lattice)
};

// Per output pixel: the front layer's weighted sums, its weight and key, and the coverage count
// (S² per covered centre, 1 per sub-sample a minified triangle covers).
struct Accumulator {
  std::vector<float> sum;  // rgba + depth, 5 per pixel
  std::vector<float> weight;
  std::vector<float> front;
  std::vector<int> count;
  int width = 0, height = 0;

  void add(size_t p, float key, float w, const float v[5]) {
    float& f = front[p];
    float* s = sum.data() + 5 * p;
    if (key > f + kKeyTolerance) {  // a layer in front: what was there is hidden
      f = key;
      for (int k = 0; k < 5; ++k) s[k] = w * v[k];
      weight[p] = w;
      return;
    }
    if (key < f - kKeyTolerance) return;  // behind the front layer
    f = std::max(f, key);
    for (int k = 0; k < 5; ++k) s[k] += w * v[k];
    weight[p] += w;
  }
};

// Which attribute jumps tear the mesh, and what a sample of a torn triangle shows.
struct TearRule {
  bool colour[4] = {false, false, false, false};  // channels the geometry reads
  bool depth = false;
  float colour_step = 0.1f;
  float depth_step = 0.05f;  // ln units

  bool joined(const Vertex& a, const Vertex& b) const {
    for (int k = 0; k < 4; ++k)
      if (colour[k] && std::abs(a.read[k] - b.read[k]) > colour_step) return false;
    return !depth || std::abs(a.key - b.key) <= depth_step;
  }
};

inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}
inline std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return -floorDiv(-a, b); }

// Edge function: twice the signed area of (a, b, p), exact.
inline std::int64_t edge(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by,
                         std::int64_t px, std::int64_t py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Top-left fill rule for a positively oriented triangle, so a sample on an edge shared by two
// triangles counts once.
inline bool topLeft(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by) {
  return (ay == by && bx < ax) || by > ay;
}

// One triangle, positively oriented, visited at the lattice points offset + step·n (lattice
// units) inside it: visit(pixel_x, pixel_y, b0, b1, b2) with barycentric weights.
template <typename Visit>
void scan(const Vertex* v[3], std::int64_t area, int offset, int step, int width_px,
          int height_px, int lattice_per_px, Visit&& visit) {
  const std::int64_t x[3] = {v[0]->fx, v[1]->fx, v[2]->fx};
  const std::int64_t y[3] = {v[0]->fy, v[1]->fy, v[2]->fy};
  const std::int64_t off = std::int64_t{offset} * kFixedOne, st = std::int64_t{step} * kFixedOne;
  const std::int64_t nx_max = std::int64_t{width_px} * lattice_per_px / step - 1;
  const std::int64_t ny_max = std::int64_t{height_px} * lattice_per_px / step - 1;
  const std::int64_t i0 = std::max<std::int64_t>(0, ceilDiv(std::min({x[0], x[1], x[2]}) - off, st));
  const std::int64_t i1 = std::min(nx_max, floorDiv(std::max({x[0], x[1], x[2]}) - off, st));
  const std::int64_t j0 = std::max<std::int64_t>(0, ceilDiv(std::min({y[0], y[1], y[2]}) - off, st));
  const std::int64_t j1 = std::min(ny_max, floorDiv(std::max({y[0], y[1], y[2]}) - off, st));
  if (i0 > i1 || j0 > j1) return;
  // Edge k is opposite vertex k: from vertex k+1 to k+2.
  const int a[3] = {1, 2, 0}, b[3] = {2, 0, 1};
  bool tl[3];
  std::int64_t dx[3], row[3];
  const std::int64_t px0 = off + i0 * st, py0 = off + j0 * st;
  for (int k = 0; k < 3; ++k) {
    tl[k] = topLeft(x[a[k]], y[a[k]], x[b[k]], y[b[k]]);
    dx[k] = -(y[b[k]] - y[a[k]]) * st;
    row[k] = edge(x[a[k]], y[a[k]], x[b[k]], y[b[k]], px0, py0);
  }
  const std::int64_t dy[3] = {(x[b[0]] - x[a[0]]) * st, (x[b[1]] - x[a[1]]) * st,
                              (x[b[2]] - x[a[2]]) * st};
  const double inv = 1.0 / static_cast<double>(area);
  const int per_px = lattice_per_px / step;  // lattice points per pixel side in this scan
  for (std::int64_t j = j0; j <= j1; ++j) {
    std::int64_t e[3] = {row[0], row[1], row[2]};
    for (std::int64_t i = i0; i <= i1; ++i) {
      if ((e[0] > 0 || (e[0] == 0 && tl[0])) && (e[1] > 0 || (e[1] == 0 && tl[1])) &&
          (e[2] > 0 || (e[2] == 0 && tl[2]))) {
        const double b0 = static_cast<double>(e[0]) * inv, b1 = static_cast<double>(e[1]) * inv;
        visit(static_cast<int>(i / per_px), static_cast<int>(j / per_px), b0, b1, 1.0 - b0 - b1);
      }
      for (int k = 0; k < 3; ++k) e[k] += dx[k];
    }
    for (int k = 0; k < 3; ++k) row[k] += dy[k];
  }
}

// How one triangle's samples are made (splat.h): linear over an intact triangle; over a torn
// one, each sample shows one side of the tear — the side it lies nearer to in barycentric
// terms, or the farther side in depth where the geometry reads depth — interpolated along
// that side alone.
struct Shading {
  const Vertex* v[3] = {nullptr, nullptr, nullptr};
  int group[3] = {0, 0, 0};
  int groups = 1;
  int chosen = -1;  // the group every sample shows (the depth rule), or -1: the nearer side
  float key = 0;    // the triangle's own key where it is constant (magnification, torn)
  bool key_from_depth = false;

  // Values (5) and key at barycentric (b0, b1, b2).
  float sample(const double bary[3], float out[5]) const {
    double w[3] = {bary[0], bary[1], bary[2]};
    if (groups > 1) {
      int g = chosen;
      if (g < 0) {
        double best = -1.0;
        for (int c = 0; c < groups; ++c) {
          double s = 0.0;
          for (int k = 0; k < 3; ++k)
            if (group[k] == c) s += w[k];
          if (s > best) {
            best = s;
            g = c;
          }
        }
      }
      double total = 0.0;
      for (int k = 0; k < 3; ++k) {
        if (group[k] != g) w[k] = 0.0;
        total += w[k];
      }
      if (total > 1e-12) {
        for (double& x : w) x /= total;
      } else {  // on the other side's vertex: the side's plain mean
        int n = 0;
        for (int k = 0; k < 3; ++k) n += group[k] == g;
        for (int k = 0; k < 3; ++k) w[k] = group[k] == g ? 1.0 / n : 0.0;
      }
    }
    for (int c = 0; c < 5; ++c)
      out[c] = static_cast<float>(w[0] * v[0]->out[c] + w[1] * v[1]->out[c] + w[2] * v[2]->out[c]);
    if (!key_from_depth) return key;
    return static_cast<float>(w[0] * v[0]->key + w[1] * v[1]->key + w[2] * v[2]->key);
  }
};

struct TriangleCounts {
  long long dropped = 0, folded = 0, torn = 0;
};

void rasterise(const Vertex& va, const Vertex& vb, const Vertex& vc, int s, int orientation,
               const TearRule& tear, Accumulator& acc, TriangleCounts& counts) {
  if (!va.side || va.side != vb.side || va.side != vc.side) {
    ++counts.dropped;
    return;
  }
  Shading sh;
  sh.v[0] = &va;
  sh.v[1] = &vb;
  sh.v[2] = &vc;
  std::int64_t area = edge(va.fx, va.fy, vb.fx, vb.fy, vc.fx, vc.fy);
  if (area == 0) return;  // degenerate: covers nothing
  // Folds: a triangle facing against the mesh is its folded-under layer, hidden. Every point
  // it covers is covered by at least two triangles facing the mesh's way (the map's degree), so
  // hiding it opens no hole.
  if (orientation != 0 && (area > 0 ? 1 : -1) != orientation) {
    ++counts.folded;
    return;
  }
  if (area < 0) {
    std::swap(sh.v[1], sh.v[2]);
    area = -area;
  }
  // Tears: group the vertices by the joins between them.
  const bool j01 = tear.joined(*sh.v[0], *sh.v[1]), j12 = tear.joined(*sh.v[1], *sh.v[2]),
             j20 = tear.joined(*sh.v[2], *sh.v[0]);
  const int joins = j01 + j12 + j20;
  if (joins >= 2) {
    sh.groups = 1;
  } else if (joins == 1) {
    sh.groups = 2;
    const int lone = j01 ? 2 : (j12 ? 0 : 1);
    for (int k = 0; k < 3; ++k) sh.group[k] = k == lone ? 1 : 0;
  } else {
    sh.groups = 3;
    for (int k = 0; k < 3; ++k) sh.group[k] = k;
  }
  const double lattice_px = 2.0 * s * static_cast<double>(kFixedOne);
  const double area_px = 0.5 * static_cast<double>(area) / (lattice_px * lattice_px);
  if (sh.groups > 1) {
    ++counts.torn;
    sh.key = kTornKey;
    if (tear.depth) {  // the disoccluded gap shows what lies behind: the farthest side
      double best = std::numeric_limits<double>::infinity();
      for (int c = 0; c < sh.groups; ++c) {
        double key = 0.0;
        int n = 0;
        for (int k = 0; k < 3; ++k)
          if (sh.group[k] == c) {
            key += sh.v[k]->key;
            ++n;
          }
        if (key / n < best) {
          best = key / n;
          sh.chosen = c;
        }
      }
    }
  } else if (tear.depth) {
    sh.key_from_depth = true;
  } else {
    // Without depth the layer the camera magnifies more lies in front (nearer things look
    // larger): the red object a positive s_red expands covers what it moves over (eq 8/9).
    sh.key = std::log(static_cast<float>(area_px));
  }

  const Vertex* v[3] = {sh.v[0], sh.v[1], sh.v[2]};
  const int lattice = 2 * s;
  const int full = s * s;
  const int w = acc.width, h = acc.height;
  float value[5];
  // One sampling rule per output pixel (splat.h): a triangle of at least ¼ px² is read at pixel
  // centres with weight S², a smaller one at the S×S sub-samples with weight 1; every covered
  // centre makes its pixel fully covered, whichever triangle covers it.
  if (area_px >= 0.25) {
    scan(v, area, s, lattice, w, h, lattice, [&](int px, int py, double b0, double b1, double b2) {
      const double bary[3] = {b0, b1, b2};
      const size_t p = static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px);
      const float key = sh.sample(bary, value);
      acc.count[p] += full;
      acc.add(p, key, static_cast<float>(full), value);
    });
    return;
  }
  scan(v, area, 1, 2, w, h, lattice, [&](int px, int py, double b0, double b1, double b2) {
    const double bary[3] = {b0, b1, b2};
    const size_t p = static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px);
    const float key = sh.sample(bary, value);
    acc.count[p] += 1;
    acc.add(p, key, 1.0f, value);
  });
  // Its centres: full coverage, and with an even S (no sub-sample there) a sample.
  const bool even = s % 2 == 0;
  scan(v, area, s, lattice, w, h, lattice, [&](int px, int py, double b0, double b1, double b2) {
    const size_t p = static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px);
    acc.count[p] += full;
    if (even) {
      const double bary[3] = {b0, b1, b2};
      const float key = sh.sample(bary, value);
      acc.add(p, key, 1.0f, value);
    }
  });
}

// The mesh's orientation: the sign of the summed signed area of a coarse mesh over the source
// (17 × 17 points, each with its own pixel's colour and depth); 0 when it has none.
int meshOrientation(const ImageF& rgba, const ImageF* depth, const AttributeEvaluator& eval,
                    FrameSize source_px, FrameSize out_px) {
  constexpr int kCells = 16;
  struct Point {
    double x = 0, y = 0;
    int side = 0;
  };
  std::vector<Point> pts(static_cast<size_t>((kCells + 1) * (kCells + 1)));
  AttributeEvaluator::Output o;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const int si = (rgba.width - 1) * i / kCells, sj = (rgba.height - 1) * j / kCells;
      const Eigen::Vector2d n = normalizedFromPixel(source_px, {si + 0.5, sj + 0.5});
      const double d = depth ? sampleDepth(*depth, source_px, si + 0.5, sj + 0.5) : 0.0;
      eval.evaluate(n.x(), n.y(), rgba.pixel(si, sj), d, o);
      Point& p = pts[static_cast<size_t>(j * (kCells + 1) + i)];
      if (!o.position_valid) continue;
      const Eigen::Vector2d t = pixelFromNormalized(out_px, {o.position[0], o.position[1]});
      if (!std::isfinite(t.x()) || !std::isfinite(t.y())) continue;
      p = {t.x(), t.y(), o.position_weight > 0 ? 1 : -1};
    }
  double total = 0.0;
  const auto at = [&](int i, int j) -> const Point& {
    return pts[static_cast<size_t>(j * (kCells + 1) + i)];
  };
  const auto add = [&](const Point& a, const Point& b, const Point& c) {
    if (!a.side || a.side != b.side || a.side != c.side) return;
    total += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return total > 0 ? 1 : (total < 0 ? -1 : 0);
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
  if (!(options.tear_colour > 0) || !(options.tear_depth > 0))
    throw std::invalid_argument("splat tear thresholds must be positive");
  if (!out_px.isImage()) throw std::invalid_argument("splat output size must be positive");
  const AttributeEvaluator eval(camera);
  if (eval.readsDepth() && (!depth || depth->empty()))
    throw std::invalid_argument("this camera reads depth: give a depth image");

  const FrameSize source_px{rgba.width, rgba.height};
  const int s = options.supersample;
  Accumulator acc;
  acc.width = out_px.width;
  acc.height = out_px.height;
  const size_t pixels = static_cast<size_t>(out_px.width) * static_cast<size_t>(out_px.height);
  acc.sum.assign(pixels * 5, 0.0f);
  acc.weight.assign(pixels, 0.0f);
  acc.front.assign(pixels, -std::numeric_limits<float>::infinity());
  acc.count.assign(pixels, 0);

  TearRule tear;
  for (int k = 0; k < 4; ++k) tear.colour[k] = eval.geometryReadsColour(k);
  tear.depth = eval.geometryReadsDepth();
  tear.colour_step = static_cast<float>(options.tear_colour);
  tear.depth_step = static_cast<float>(std::log1p(options.tear_depth));
  const int orientation = meshOrientation(rgba, depth, eval, source_px, out_px);
  const double to_fixed = 2.0 * s * static_cast<double>(kFixedOne);

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
      const float* in = rgba.pixel(si, sj);
      eval.evaluate(n.x(), n.y(), in, d, o);
      Vertex& v = row[static_cast<size_t>(i + 1)];
      v = Vertex{};
      std::copy(in, in + 4, v.read);
      v.read[4] = static_cast<float>(d);
      v.key = d > 0.0 ? static_cast<float>(-std::log(d)) : 0.0f;
      if (!o.position_valid) continue;
      const Eigen::Vector2d t = pixelFromNormalized(out_px, {o.position[0], o.position[1]});
      const double fx = std::round(t.x() * to_fixed), fy = std::round(t.y() * to_fixed);
      // Beyond the lattice's exact range (far outside the frame, near a pole): no position.
      if (!(std::abs(fx) < static_cast<double>(kFixedLimit)) ||
          !(std::abs(fy) < static_cast<double>(kFixedLimit)))
        continue;
      v.fx = static_cast<std::int64_t>(fx);
      v.fy = static_cast<std::int64_t>(fy);
      v.side = o.position_weight > 0 ? 1 : -1;
      v.out[4] = o.depth;
      if (!outside && o.attributes_valid) std::copy(o.rgba, o.rgba + 4, v.out);
    }
  };

  // Bands of source rows: their vertex rows mapped in parallel, then rasterised in order.
  constexpr int kBand = 32;
  std::vector<std::vector<Vertex>> rows;
  std::vector<Vertex> carry;  // the last vertex row of the previous band
  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = 4;
  TriangleCounts counts;
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
        rasterise(v00, v10, v11, s, orientation, tear, acc, counts);
        rasterise(v00, v11, v01, s, orientation, tear, acc, counts);
      }
    }
    carry = std::move(rows.back());
    if (options.progress && !options.progress(static_cast<double>(j1 + 1) / (rgba.height + 1))) {
      report.cancelled = true;
      return {};
    }
  }
  report.dropped_triangles = counts.dropped;
  report.folded_triangles = counts.folded;
  report.torn_triangles = counts.torn;

  AttributedImage out;
  out.colour = ImageF(out_px.width, out_px.height, 4, 3);
  if (eval.readsDepth()) out.depth = ImageF(out_px.width, out_px.height, 1);
  const float full = static_cast<float>(s * s);
  for (size_t p = 0; p < pixels; ++p) {
    const int n = acc.count[p];
    const float wsum = acc.weight[p];
    float* c = out.colour.data.data() + 4 * p;
    if (n == 0 || !(wsum > 0.0f)) {
      ++report.transparent_pixels;
      continue;
    }
    // The front layer's weighted mean, at the pixel's coverage (splat.h).
    const float coverage = std::min(1.0f, static_cast<float>(n) / full);
    const float norm = coverage / wsum;
    for (int k = 0; k < 4; ++k) c[k] = acc.sum[5 * p + static_cast<size_t>(k)] * norm;
    c[3] = std::clamp(c[3], 0.0f, 1.0f);
    if (!(c[3] > 0.0f)) {
      std::fill(c, c + 4, 0.0f);
      ++report.transparent_pixels;
      continue;
    }
    if (!out.depth.empty()) out.depth.data[p] = acc.sum[5 * p + 4] / wsum;
  }
  return out;
}

}  // namespace artcam
