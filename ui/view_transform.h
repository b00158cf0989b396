// SPDX-License-Identifier: Apache-2.0
// The one object that owns widget ↔ image coordinates for a canvas (after Krita's
// KisCoordinatesConverter). Image coordinates are photo PIXELS with (0, 0) the top-left corner
// of the top-left pixel, as in the engine; widget coordinates are logical widget pixels.
//   widget = image * scale + offset
#pragma once

#include <QPointF>
#include <QRectF>
#include <QSizeF>
#include <QTransform>

namespace artcam::ui {

class ViewTransform {
 public:
  static constexpr double kMinScale = 1.0 / 64.0;
  static constexpr double kMaxScale = 64.0;

  double scale() const { return scale_; }
  QPointF offset() const { return offset_; }

  QPointF widgetFromImage(const QPointF& image) const { return image * scale_ + offset_; }
  QPointF imageFromWidget(const QPointF& widget) const { return (widget - offset_) / scale_; }
  QRectF widgetFromImage(const QRectF& image) const;
  QTransform widgetFromImageTransform() const;

  // The whole image centred in the widget with a small margin.
  void fit(const QSizeF& widget, const QSizeF& image);
  // Zoom by `factor` keeping the image point under `widget_anchor` fixed.
  void zoomAt(double factor, const QPointF& widget_anchor);
  // Absolute scale keeping the image point under `widget_anchor` fixed.
  void setScaleAt(double scale, const QPointF& widget_anchor);
  void panBy(const QPointF& widget_delta) { offset_ += widget_delta; }
  // The image point at the widget centre (saved in projects, independent of widget size).
  QPointF centre(const QSizeF& widget) const;
  void setCentre(const QSizeF& widget, const QPointF& image_point);

 private:
  double scale_ = 1.0;
  QPointF offset_{0.0, 0.0};
};

}  // namespace artcam::ui
