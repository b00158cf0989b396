// SPDX-License-Identifier: Apache-2.0
#include "ui/depth_mask_tint.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

namespace {

QRgb tinted(const QColor& colour, uint8_t coverage) {
  const double a = kMaskTintOpacity * coverage / 255.0;
  return qRgba(static_cast<int>(std::lround(colour.red() * a)),
               static_cast<int>(std::lround(colour.green() * a)),
               static_cast<int>(std::lround(colour.blue() * a)),
               static_cast<int>(std::lround(255 * a)));
}

}  // namespace

FrameSize maskTintSize(const RegionMask& mask, int max_side) {
  if (mask.empty() || max_side < 1) return {0, 0};
  const double shrink =
      std::min(1.0, static_cast<double>(max_side) / std::max(mask.width(), mask.height()));
  return {std::max(1, static_cast<int>(std::lround(mask.width() * shrink))),
          std::max(1, static_cast<int>(std::lround(mask.height() * shrink)))};
}

QImage maskTint(const RegionMask& mask, const QColor& colour, int max_side) {
  const FrameSize size = maskTintSize(mask, max_side);
  const int w = size.width, h = size.height;
  if (w < 1 || h < 1) return {};
  QImage out(w, h, QImage::Format_ARGB32_Premultiplied);
  for (int j = 0; j < h; ++j) {
    auto* row = reinterpret_cast<QRgb*>(out.scanLine(j));
    const int my = std::min(mask.height() - 1, static_cast<int>((j + 0.5) * mask.height() / h));
    for (int i = 0; i < w; ++i) {
      const int mx = std::min(mask.width() - 1, static_cast<int>((i + 0.5) * mask.width() / w));
      row[i] = tinted(colour, mask.at(mx, my));
    }
  }
  return out;
}

QImage maskTintThrough(const RegionMask& mask, const QColor& colour, FrameSize grid,
                       const std::vector<Eigen::Vector2f>& photo_px) {
  if (mask.empty() || grid.width < 1 || grid.height < 1 ||
      photo_px.size() != static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height))
    return {};
  QImage out(grid.width, grid.height, QImage::Format_ARGB32_Premultiplied);
  for (int j = 0; j < grid.height; ++j) {
    auto* row = reinterpret_cast<QRgb*>(out.scanLine(j));
    for (int i = 0; i < grid.width; ++i) {
      const Eigen::Vector2f& p = photo_px[static_cast<size_t>(j) * grid.width + i];
      // The mask pixel under the photo point (NaN fails both tests: transparent).
      const bool inside =
          p.x() >= 0.0f && p.y() >= 0.0f && p.x() < mask.width() && p.y() < mask.height();
      row[i] = inside ? tinted(colour, mask.at(static_cast<int>(p.x()), static_cast<int>(p.y())))
                      : qRgba(0, 0, 0, 0);
    }
  }
  return out;
}

}  // namespace artcam::ui
