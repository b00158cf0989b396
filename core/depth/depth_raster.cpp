// SPDX-License-Identifier: Apache-2.0
#include "core/depth/depth_raster.h"

#include "core/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace artcam {

ImageF rasteriseDepth(const std::vector<DepthLayer>& layers, int photo_width, int photo_height,
                      const ImageF* base_map, const DepthRasterOptions& options,
                      DepthRasterSummary* summary) {
  if (photo_width <= 0 || photo_height <= 0)
    throw std::invalid_argument("rasteriseDepth: empty photo frame");
  for (const DepthLayer& layer : layers)
    if (!layer.mask || layer.mask->width() != photo_width || layer.mask->height() != photo_height)
      throw std::invalid_argument("rasteriseDepth: a layer's mask is not the photo's size");
  if (base_map && (base_map->empty() || base_map->channels < 1 || base_map->channels > 2))
    throw std::invalid_argument(
        "rasteriseDepth: the base map must be a 1- or 2-channel depth image");
  if (!(options.max_depth > 0.0) || !std::isfinite(options.max_depth))
    throw std::invalid_argument("rasteriseDepth: max_depth must be finite and positive");

  const int w = options.width > 0 ? options.width : photo_width;
  const int h = options.height > 0 ? options.height : photo_height;
  const double sx = static_cast<double>(photo_width) / w;
  const double sy = static_cast<double>(photo_height) / h;
  const double min_inverse = 1.0 / options.max_depth;
  ImageF out(w, h, 2, 1);
  std::atomic<size_t> clamped{0};

  ParallelOptions parallel;
  parallel.threads = options.threads;
  parallel.progress = options.progress;
  const bool done = parallelForRows(h, parallel, [&](int y0, int y1) {
    size_t band_clamped = 0;
    for (int j = y0; j < y1; ++j) {
      const double py = (j + 0.5) * sy;
      const int my = std::min(photo_height - 1, static_cast<int>(py));
      for (int i = 0; i < w; ++i) {
        const double px = (i + 0.5) * sx;
        const int mx = std::min(photo_width - 1, static_cast<int>(px));
        double inv = 0.0;  // premultiplied inverse depth
        double alpha = 0.0;
        if (base_map) {
          const int bx =
              std::min(base_map->width - 1, static_cast<int>(px * base_map->width / photo_width));
          const int by = std::min(base_map->height - 1,
                                  static_cast<int>(py * base_map->height / photo_height));
          const float* b = base_map->pixel(bx, by);
          // (a·z, a), or z alone (depth_file.h: coverage 1 where z > 0).
          const double a = base_map->channels == 2 ? std::min(1.0, static_cast<double>(b[1])) : 1.0;
          if (a > 0.0 && b[0] > 0.0f && std::isfinite(b[0])) {
            alpha = a;
            inv = a * a / static_cast<double>(b[0]);  // a · (1/z), z = ch0/a
          }
        }
        for (const DepthLayer& layer : layers) {
          if (!layer.plane) continue;
          const uint8_t c = layer.mask->at(mx, my);
          if (c == 0) continue;
          const double a = c / 255.0;
          double v = layer.plane->inverseDepthAt(px, py);
          if (!(v >= min_inverse)) {  // also catches NaN
            v = min_inverse;
            ++band_clamped;
          }
          inv = a * v + (1.0 - a) * inv;
          alpha = a + (1.0 - a) * alpha;
        }
        float* o = out.pixel(i, j);
        if (alpha > 0.0 && inv > 0.0) {
          const double z = alpha / inv;  // 1 / (inv / alpha)
          o[0] = static_cast<float>(alpha * z);
          o[1] = static_cast<float>(alpha);
        }
      }
    }
    clamped += band_clamped;
  });

  if (summary) {
    *summary = DepthRasterSummary{};
    summary->cancelled = !done;
    summary->clamped = clamped.load();
    bool first = true;
    for (int j = 0; j < h && done; ++j)
      for (int i = 0; i < w; ++i) {
        const float* o = out.pixel(i, j);
        if (o[1] <= 0.0f) continue;
        const double z = static_cast<double>(o[0]) / o[1];
        ++summary->covered;
        summary->min_depth = first ? z : std::min(summary->min_depth, z);
        summary->max_depth = first ? z : std::max(summary->max_depth, z);
        first = false;
      }
  }
  return out;
}

std::optional<double> depthAt(const ImageF& depth, int x, int y) {
  if (depth.channels < 1 || depth.channels > 2 || x < 0 || y < 0 || x >= depth.width ||
      y >= depth.height)
    return std::nullopt;
  const float* p = depth.pixel(x, y);
  if (depth.channels == 1) {  // z alone, 0 = none (depth_file.h)
    if (!(p[0] > 0.0f) || !std::isfinite(p[0])) return std::nullopt;
    return static_cast<double>(p[0]);
  }
  if (!(p[1] > 0.0f)) return std::nullopt;
  return static_cast<double>(p[0]) / p[1];
}

std::string depthMapAspectNote(FrameSize map, FrameSize photo) {
  if (!map.isImage() || !photo.isImage()) return {};
  // The map's height at the photo's aspect, in the map's pixels.
  const double expected_height = static_cast<double>(photo.height) * map.width / photo.width;
  if (std::abs(map.height - expected_height) <= 1.0) return {};
  return "the depth map is " + std::to_string(map.width) + "x" + std::to_string(map.height) +
         " but the photo is " + std::to_string(photo.width) + "x" + std::to_string(photo.height) +
         " (another aspect): depth is stretched per axis";
}

}  // namespace artcam
