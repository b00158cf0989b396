// SPDX-License-Identifier: Apache-2.0
// Draws a large image minified into a rectangle through a copy scaled to that rectangle's size
// (smooth; made once per image and size), so a repaint — one per mouse move of a drag — copies
// pixels instead of filtering the 4096-px display copy again (about 10 ms per paint on the
// studio's 2-core machines). Magnified images are drawn directly (nearest or smooth as the
// painter's hints say), as before.
#pragma once

#include <QImage>
#include <QPainter>
#include <QRectF>
#include <QSize>

namespace artcam::ui {

class ScaledImageCache {
 public:
  void draw(QPainter& painter, const QRectF& target, const QImage& image) {
    const QSize size = target.size().toSize();
    if (image.isNull() || size.width() >= image.width() || size.height() >= image.height() ||
        size.isEmpty() || !painter.transform().isIdentity()) {
      painter.drawImage(target, image);
      return;
    }
    if (image.cacheKey() != key_ || size != scaled_.size()) {
      scaled_ = image.scaled(size, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
      key_ = image.cacheKey();
    }
    painter.drawImage(QRectF(target.topLeft(), QSizeF(size)), scaled_);
  }

 private:
  qint64 key_ = 0;
  QImage scaled_;
};

}  // namespace artcam::ui
