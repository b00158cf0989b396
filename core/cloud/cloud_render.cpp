// SPDX-License-Identifier: Apache-2.0
// Cloud rendering in two passes: (1) every point through the chain, in parallel chunks, into a
// flat splat list; (2) splats binned by bands of image rows, each band drawn by one worker in
// point order, so no two threads touch a pixel and ties resolve the same way every run.
#include "core/cloud/cloud_render.h"

#include "core/model/compiled_camera.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace artcam {

double CloudRenderSummary::pointsPerSecond() const {
  return render_ms > 0 ? static_cast<double>(points) / (render_ms / 1000.0) : 0.0;
}

namespace {

struct CompiledStage {
  CompiledCamera camera;
  int position = -1;  // offsets of the blocks in x
  int colour = -1;
  int depth = -1;
  int shading = -1;
};

// The chain of cameras a point passes through.
class Chain {
 public:
  explicit Chain(const std::vector<const Camera*>& cameras) {
    for (const Camera* c : cameras) {
      CompiledStage s{CompiledCamera(*c)};
      if (s.camera.isIdentity() && c != cameras.back()) continue;  // nothing to do
      const BlockLayout& l = s.camera.layout();
      const int p = l.find(BlockKind::Position);
      if (p < 0 || l.blocks[p].size != 4)
        throw std::invalid_argument(
            "an object-space camera needs a 4-element position block (X, Y, Z, 1)");
      s.position = l.offsets[p];
      if (const int c_block = l.find(BlockKind::Colour); c_block >= 0)
        s.colour = l.offsets[c_block];
      if (const int d_block = l.find(BlockKind::Depth); d_block >= 0) s.depth = l.offsets[d_block];
      if (const int b = l.find(BlockKind::Shading); b >= 0) s.shading = l.offsets[b];
      stages_.push_back(std::move(s));
    }
    reads_colour_after_.assign(stages_.size(), false);
    for (size_t k = stages_.size(); k-- > 1;)
      reads_colour_after_[k - 1] = reads_colour_after_[k] || stages_[k].colour >= 0;
  }
  bool readsColour() const {
    return std::any_of(stages_.begin(), stages_.end(),
                       [](const CompiledStage& s) { return s.colour >= 0; });
  }

  // Maps p (and its premultiplied colour, updated in place); false where it does not map.
  // With `geometry_only` colour outputs are computed only where a later camera reads them.
  bool map(const Eigen::Vector3d& p, Eigen::Vector4f& colour, Eigen::Vector3d& out,
           bool geometry_only = false) const {
    Eigen::Vector3d point = p;
    for (size_t st = 0; st < stages_.size(); ++st) {
      const CompiledStage& s = stages_[st];
      const bool skip_colour = geometry_only && !reads_colour_after_[st];
      CompiledCamera::Vector x{}, y;
      for (int k = 0; k < 3; ++k) x[s.position + k] = point[k];
      x[s.position + 3] = 1.0;
      if (s.colour >= 0)
        for (int k = 0; k < 4; ++k) x[s.colour + k] = colour[k];
      if (s.depth >= 0) x[s.depth + 1] = 1.0;
      if (s.shading >= 0) x[s.shading + 1] = 1.0;  // (0, 1): the camera computes it (camera.h)
      s.camera.evaluate(x, y, skip_colour);
      for (int i = 0; i < 3; ++i) point[i] = y[s.position + i];
      if (!point.allFinite()) return false;
      if (s.colour >= 0 && !skip_colour) {
        const double a = y[s.colour + 3];  // eq 5: rgb divided by alpha, alpha clamped
        for (int k = 0; k < 3; ++k)
          colour[k] = a > 0 ? static_cast<float>(y[s.colour + k] * a) : 0.0f;
        colour[3] = static_cast<float>(a);
      }
    }
    out = point;
    return true;
  }

 private:
  std::vector<CompiledStage> stages_;
  std::vector<bool> reads_colour_after_;  // some later stage reads colour
};

std::vector<const Camera*> pointers(const std::vector<Camera>& effects, const Camera* view) {
  std::vector<const Camera*> out;
  for (const Camera& c : effects) out.push_back(&c);
  if (view) out.push_back(view);
  return out;
}

struct Splat {
  float x = 0, y = 0, radius = 0, nearness = 0;  // radius 0: dropped
  Eigen::Vector4f colour = Eigen::Vector4f::Zero();
};

constexpr int kChunk = 4096;
constexpr int kBandRows = 16;

// Pass 1: the splats of every point, carrying colour channel `layer` only (or all for -1).
std::vector<Splat> project(const PointCloud& cloud, const Chain& chain, double spacing, int layer,
                           const CloudRenderOptions& o, bool& cancelled) {
  std::vector<Splat> splats(cloud.size());
  const double s = std::max(o.width, o.height) / 2.0;  // frames.h: normalised → pixels
  const int chunks = static_cast<int>((cloud.size() + kChunk - 1) / kChunk);
  ParallelOptions po;
  po.threads = o.threads;
  po.band_rows = 1;
  if (o.progress) po.progress = [&](double f) { return o.progress(0.8 * f); };
  const bool done = parallelForRows(chunks, po, [&](int c0, int c1) {
    const size_t end = std::min(cloud.size(), static_cast<size_t>(c1) * kChunk);
    for (size_t i = static_cast<size_t>(c0) * kChunk; i < end; ++i) {
      const Eigen::Vector3d& p = cloud.positions[i];
      Eigen::Vector4f base = cloud.colour(i);
      if (layer >= 0)
        for (int k = 0; k < 3; ++k)
          if (k != layer) base[k] = 0.0f;
      Eigen::Vector4f colour = base;
      Eigen::Vector3d o3;
      if (!p.allFinite() || !chain.map(p, colour, o3) || !(o3[2] > 0) || !(colour[3] > 0)) continue;
      const double px = o.width / 2.0 + s * o3[0], py = o.height / 2.0 + s * o3[1];
      double step = 0.0;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d q = p;
        q[k] += spacing;
        Eigen::Vector4f cq = base;
        Eigen::Vector3d oq;
        if (chain.map(q, cq, oq, true))
          step = std::max(step, (oq.head<2>() - o3.head<2>()).squaredNorm());
      }
      step = s * std::sqrt(step);
      if (!std::isfinite(px) || !std::isfinite(py) || !std::isfinite(step)) continue;
      Splat& sp = splats[i];
      sp.x = static_cast<float>(px);
      sp.y = static_cast<float>(py);
      sp.radius = static_cast<float>(std::clamp(o.splat_scale * step, 0.5, o.max_splat_px));
      sp.nearness = static_cast<float>(o3[2]);
      sp.colour = colour;
    }
  });
  cancelled = !done;
  return splats;
}

struct Rows {
  int first = 0, last = -1;  // pixel rows whose centres the disc covers
};
Rows coveredRows(const Splat& sp, int height) {
  return {std::max(0, static_cast<int>(std::ceil(sp.y - sp.radius - 0.5f))),
          std::min(height - 1, static_cast<int>(std::floor(sp.y + sp.radius - 0.5f)))};
}

// Pass 2: z-buffered discs. Returns the number of splats that reached the image.
size_t splat(const std::vector<Splat>& splats, const CloudRenderOptions& o, ImageF& image,
             std::vector<float>& zbuffer, bool& cancelled) {
  const int w = o.width, h = o.height;
  const int bands = (h + kBandRows - 1) / kBandRows;
  std::vector<std::uint32_t> start(static_cast<size_t>(bands) + 1, 0);
  size_t drawn = 0;
  const auto visible = [&](const Splat& sp, Rows& rows) {
    if (sp.radius <= 0) return false;
    rows = coveredRows(sp, h);
    return rows.first <= rows.last && sp.x + sp.radius > 0.5f && sp.x - sp.radius < w - 0.5f;
  };
  Rows rows;
  for (const Splat& sp : splats)
    if (visible(sp, rows)) {
      ++drawn;
      for (int b = rows.first / kBandRows; b <= rows.last / kBandRows; ++b) ++start[b + 1];
    }
  for (int b = 0; b < bands; ++b) start[b + 1] += start[b];
  std::vector<std::uint32_t> members(start[bands]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < splats.size(); ++i)
    if (visible(splats[i], rows))
      for (int b = rows.first / kBandRows; b <= rows.last / kBandRows; ++b)
        members[fill[b]++] = static_cast<std::uint32_t>(i);

  ParallelOptions po;
  po.threads = o.threads;
  po.band_rows = 1;
  if (o.progress) po.progress = [&](double f) { return o.progress(0.8 + 0.2 * f); };
  const bool done = parallelForRows(bands, po, [&](int b0, int b1) {
    for (int b = b0; b < b1; ++b) {
      const int y0 = b * kBandRows, y1 = std::min(h, y0 + kBandRows);
      for (std::uint32_t m = start[b]; m < start[b + 1]; ++m) {
        const Splat& sp = splats[members[m]];
        const Rows r = coveredRows(sp, h);
        for (int iy = std::max(r.first, y0); iy <= std::min(r.last, y1 - 1); ++iy) {
          const float dy = iy + 0.5f - sp.y;
          const float half = std::sqrt(std::max(0.0f, sp.radius * sp.radius - dy * dy));
          const int x0 = std::max(0, static_cast<int>(std::ceil(sp.x - half - 0.5f)));
          const int x1 = std::min(w - 1, static_cast<int>(std::floor(sp.x + half - 0.5f)));
          for (int ix = x0; ix <= x1; ++ix) {
            float& z = zbuffer[static_cast<size_t>(iy) * w + ix];
            if (sp.nearness <= z) continue;  // ties: the earlier point stays
            z = sp.nearness;
            float* px = image.pixel(ix, iy);
            for (int k = 0; k < 4; ++k) px[k] = sp.colour[k];
          }
        }
      }
    }
  });
  if (!done) cancelled = true;
  return drawn;
}

}  // namespace

ImageF renderCloud(const PointCloud& cloud, const std::vector<Camera>& effects, const Camera& view,
                   const CloudRenderOptions& options, CloudRenderSummary* summary) {
  if (options.width <= 0 || options.height <= 0)
    throw std::invalid_argument("renderCloud: the image size must be positive");
  if (cloud.hasColour() && cloud.colours.size() != cloud.size())
    throw std::invalid_argument("renderCloud: colours and positions differ in count");
  const auto t0 = std::chrono::steady_clock::now();
  const Chain chain(pointers(effects, &view));
  CloudRenderSummary s;
  s.point_spacing = options.point_spacing > 0 ? options.point_spacing : estimatePointSpacing(cloud);
  if (!(s.point_spacing > 0))
    s.point_spacing = 1e-3 * std::max(1e-300, cloudBounds(cloud).radius());

  ImageF image(options.width, options.height, 4, 3);
  const size_t pixels = static_cast<size_t>(options.width) * static_cast<size_t>(options.height);
  const std::vector<int> layers =
      options.layers == RenderLayers::Rgb ? std::vector<int>{0, 1, 2} : std::vector<int>{-1};
  for (size_t pass_index = 0; pass_index < layers.size(); ++pass_index) {
    const int layer = layers[pass_index];
    // Progress over all passes: pass k covers [k/n, (k+1)/n].
    CloudRenderOptions pass_options = options;
    if (options.progress) {
      const double n = static_cast<double>(layers.size());
      pass_options.progress = [&options, pass_index, n](double f) {
        return options.progress((static_cast<double>(pass_index) + f) / n);
      };
    }
    std::vector<Splat> splats =
        project(cloud, chain, s.point_spacing, layer, pass_options, s.cancelled);
    if (s.cancelled) break;
    ImageF pass(options.width, options.height, 4, 3);
    std::vector<float> zbuffer(pixels, -std::numeric_limits<float>::infinity());
    s.points += splats.size();
    const size_t drawn = splat(splats, pass_options, pass, zbuffer, s.cancelled);
    s.drawn += drawn;
    for (const Splat& sp : splats) s.dropped += sp.radius <= 0;
    if (layer < 0) {
      image = std::move(pass);
    } else {
      for (size_t p = 0; p < pixels; ++p) {
        image.data[p * 4 + layer] = pass.data[p * 4 + layer];
        image.data[p * 4 + 3] = std::max(image.data[p * 4 + 3], pass.data[p * 4 + 3]);
      }
    }
  }
  s.render_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (summary) *summary = s;
  return image;
}

PointCloud applyCameras(const PointCloud& cloud, const std::vector<Camera>& effects, int threads,
                        size_t* dropped) {
  const Chain chain(pointers(effects, nullptr));
  const bool colour = cloud.hasColour() || chain.readsColour();
  std::vector<Eigen::Vector3d> positions(cloud.size());
  std::vector<Eigen::Vector4f> colours(colour ? cloud.size() : 0);
  std::vector<char> ok(cloud.size(), 0);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 1;
  const int chunks = static_cast<int>((cloud.size() + kChunk - 1) / kChunk);
  parallelForRows(chunks, po, [&](int c0, int c1) {
    const size_t end = std::min(cloud.size(), static_cast<size_t>(c1) * kChunk);
    for (size_t i = static_cast<size_t>(c0) * kChunk; i < end; ++i) {
      Eigen::Vector4f c = cloud.colour(i);
      ok[i] = cloud.positions[i].allFinite() && chain.map(cloud.positions[i], c, positions[i]);
      if (colour) colours[i] = c;
    }
  });
  PointCloud out;
  out.has_alpha = cloud.has_alpha;
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (!ok[i]) continue;
    out.positions.push_back(positions[i]);
    if (colour) out.colours.push_back(colours[i]);
  }
  if (dropped) *dropped = cloud.size() - out.size();
  return out;
}

CameraPose defaultViewPose(const CloudBounds& bounds) {
  const Eigen::Vector3d at = bounds.empty ? Eigen::Vector3d::Zero() : bounds.centre();
  const double r = bounds.radius() > 0 ? bounds.radius() : 1.0;
  return CameraPose::lookAt(at + 2.8 * r * Eigen::Vector3d(4, 3, -5).normalized(), at);
}

PinholeParams framingPinhole(const PointCloud& cloud, const CameraPose& pose, int width, int height,
                             double margin) {
  double ax = 0.0, ay = 0.0;
  for (const Eigen::Vector3d& p : cloud.positions) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d c = pose.cameraFromWorld(p);
    if (!(c.z() > 0)) continue;
    ax = std::max(ax, std::abs(c.x() / c.z()));
    ay = std::max(ay, std::abs(c.y() / c.z()));
  }
  const double s = std::max(width, height) / 2.0;
  const double lx = width / 2.0 / s, ly = height / 2.0 / s;  // half extents, normalised frame
  double f = std::numeric_limits<double>::infinity();
  if (ax > 0) f = std::min(f, lx / ax);
  if (ay > 0) f = std::min(f, ly / ay);
  PinholeParams p;
  p.pose = pose;
  p.focal = std::isfinite(f) ? f / std::max(1.0, margin) : 2.0;
  return p;
}

}  // namespace artcam
