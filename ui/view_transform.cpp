// SPDX-License-Identifier: Apache-2.0
#include "ui/view_transform.h"

#include <algorithm>

namespace artcam::ui {

QRectF ViewTransform::widgetFromImage(const QRectF& image) const {
  return {widgetFromImage(image.topLeft()), widgetFromImage(image.bottomRight())};
}

QTransform ViewTransform::widgetFromImageTransform() const {
  return QTransform(scale_, 0.0, 0.0, scale_, offset_.x(), offset_.y());
}

void ViewTransform::fit(const QSizeF& widget, const QSizeF& image) {
  if (image.isEmpty() || widget.isEmpty()) return;
  constexpr double kMargin = 8.0;
  const double sx = std::max(1.0, widget.width() - 2 * kMargin) / image.width();
  const double sy = std::max(1.0, widget.height() - 2 * kMargin) / image.height();
  scale_ = std::clamp(std::min(sx, sy), kMinScale, kMaxScale);
  offset_ = QPointF((widget.width() - image.width() * scale_) / 2,
                    (widget.height() - image.height() * scale_) / 2);
}

void ViewTransform::zoomAt(double factor, const QPointF& widget_anchor) {
  setScaleAt(scale_ * factor, widget_anchor);
}

void ViewTransform::setScaleAt(double scale, const QPointF& widget_anchor) {
  const QPointF image_anchor = imageFromWidget(widget_anchor);
  scale_ = std::clamp(scale, kMinScale, kMaxScale);
  offset_ = widget_anchor - image_anchor * scale_;
}

QPointF ViewTransform::centre(const QSizeF& widget) const {
  return imageFromWidget(QPointF(widget.width() / 2, widget.height() / 2));
}

void ViewTransform::setCentre(const QSizeF& widget, const QPointF& image_point) {
  offset_ = QPointF(widget.width() / 2, widget.height() / 2) - image_point * scale_;
}

}  // namespace artcam::ui
