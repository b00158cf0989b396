// SPDX-License-Identifier: Apache-2.0
#include "ui/depth_mask_tint.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

QImage maskTint(const RegionMask& mask, const QColor& colour, int max_side) {
  if (mask.empty() || max_side < 1) return {};
  const double shrink =
      std::min(1.0, static_cast<double>(max_side) / std::max(mask.width(), mask.height()));
  const int w = std::max(1, static_cast<int>(std::lround(mask.width() * shrink)));
  const int h = std::max(1, static_cast<int>(std::lround(mask.height() * shrink)));
  QImage out(w, h, QImage::Format_ARGB32_Premultiplied);
  for (int j = 0; j < h; ++j) {
    auto* row = reinterpret_cast<QRgb*>(out.scanLine(j));
    const int my = std::min(mask.height() - 1, static_cast<int>((j + 0.5) * mask.height() / h));
    for (int i = 0; i < w; ++i) {
      const int mx = std::min(mask.width() - 1, static_cast<int>((i + 0.5) * mask.width() / w));
      const double a = kMaskTintOpacity * mask.at(mx, my) / 255.0;
      row[i] = qRgba(static_cast<int>(std::lround(colour.red() * a)),
                     static_cast<int>(std::lround(colour.green() * a)),
                     static_cast<int>(std::lround(colour.blue() * a)),
                     static_cast<int>(std::lround(255 * a)));
    }
  }
  return out;
}

}  // namespace artcam::ui
