// SPDX-License-Identifier: Apache-2.0
#include "ui/depth_overlay.h"

#include "core/depth/depth_raster.h"
#include "ui/document.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

DepthOverlay::DepthOverlay(Document* document, QObject* parent)
    : QObject(parent), document_(document) {
  trailing_.setSingleShot(true);
  trailing_.setInterval(kThrottleMs);
  connect(&trailing_, &QTimer::timeout, this, [this] {
    if (pending_) update();
  });
  connect(document_->depth(), &DepthModel::depthChanged, this, &DepthOverlay::schedule);
}

void DepthOverlay::schedule() {
  // Leading edge: the first change shows at once; later ones within the interval coalesce
  // into one trailing update.
  if (trailing_.isActive()) {
    pending_ = true;
    return;
  }
  update();
  trailing_.start();
}

void DepthOverlay::setVisible(bool visible) {
  if (visible == visible_) return;
  visible_ = visible;
  emit changed();
}

void DepthOverlay::setOpacity(double opacity) {
  opacity = std::clamp(opacity, 0.0, 1.0);
  if (opacity == opacity_) return;
  opacity_ = opacity;
  emit changed();
}

QColor DepthOverlay::ramp(double t) {
  // A short turbo-like ramp: far deep blue → cyan → green → yellow → near red.
  static const double stops[5][3] = {
      {48, 18, 120}, {40, 140, 250}, {40, 210, 130}, {245, 205, 45}, {200, 30, 20}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4.0;
  const int k = std::min(3, static_cast<int>(t));
  const double f = t - k;
  auto mix = [&](int c) {
    return static_cast<int>(std::lround(stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f));
  };
  return QColor(mix(0), mix(1), mix(2));
}

QColor DepthOverlay::colourFor(double depth) const {
  if (!(max_depth_ > 0.0) || !(depth > 0.0)) return QColor(Qt::transparent);
  const double far_inv = 1.0 / max_depth_, near_inv = 1.0 / min_depth_;
  const double t = near_inv > far_inv ? (1.0 / depth - far_inv) / (near_inv - far_inv) : 0.5;
  return ramp(t);
}

void DepthOverlay::update() {
  pending_ = false;
  const DepthModel* depth = document_->depth();
  const FrameSize f = depth->frame();
  image_ = QImage();
  raster_.reset();
  min_depth_ = max_depth_ = 0.0;
  if (f.isImage() && depth->hasDepth()) {
    const double s = std::min(1.0, static_cast<double>(kMaxSide) / std::max(f.width, f.height));
    DepthRasterOptions options;
    options.width = std::max(1, static_cast<int>(std::lround(f.width * s)));
    options.height = std::max(1, static_cast<int>(std::lround(f.height * s)));
    options.threads = 1;
    DepthRasterSummary summary;
    auto shared = std::make_shared<const ImageF>(depth->rasterise(options, &summary));
    const ImageF& raster = *shared;
    if (summary.covered > 0) {
      raster_ = std::move(shared);
      min_depth_ = summary.min_depth;
      max_depth_ = summary.max_depth;
      image_ = QImage(raster.width, raster.height, QImage::Format_ARGB32_Premultiplied);
      for (int y = 0; y < raster.height; ++y) {
        auto* line = reinterpret_cast<QRgb*>(image_.scanLine(y));
        for (int x = 0; x < raster.width; ++x) {
          const float* p = raster.pixel(x, y);
          if (!(p[1] > 0.0f)) {
            line[x] = 0;
            continue;
          }
          const QColor c = colourFor(static_cast<double>(p[0]) / p[1]);
          const int a = static_cast<int>(std::lround(255.0 * std::min(1.0f, p[1])));
          line[x] = qPremultiply(qRgba(c.red(), c.green(), c.blue(), a));
        }
      }
    }
  }
  emit changed();
}

}  // namespace artcam::ui
