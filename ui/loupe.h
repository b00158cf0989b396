// SPDX-License-Identifier: Apache-2.0
// The loupe: a magnified, nearest-neighbour view of the photo around the
// cursor, drawn in a corner of the canvas away from the cursor while a tool places or drags a
// point, with a crosshair on the exact sub-pixel cursor position, so points can be placed to a
// fraction of a pixel without zooming the whole view.
//
// Frames: `image_point` is in photo PIXELS (centres at i + 0.5); the display picture may be a
// downscaled copy (Photo::display), so it is sampled at image × display_width / photo_width.
#pragma once

#include <QImage>
#include <QPointF>
#include <QRectF>
#include <QSize>

class QPainter;

namespace artcam::ui {

struct LoupeGeometry {
  QRectF widget_rect;   // where the loupe is drawn (widget pixels)
  QPointF image_centre; // photo pixel position at its centre (the cursor's)
  double scale = 0.0;   // widget pixels per photo pixel inside the loupe

  bool isValid() const { return !widget_rect.isEmpty() && scale > 0.0; }
  // Photo pixel position shown at a widget point inside the loupe.
  QPointF imageFromWidget(const QPointF& w) const {
    return image_centre + (w - widget_rect.center()) / scale;
  }
};

class Loupe {
 public:
  static constexpr int kSide = 168;            // widget pixels
  static constexpr double kMagnification = 6;  // × the canvas's own scale
  static constexpr double kMinScale = 8;       // at least 8 widget px per photo pixel
  static constexpr double kMaxScale = 64;
  static constexpr int kMargin = 10;

  // The loupe for a cursor at `cursor_widget` (image point `image_point`) on a canvas of
  // `canvas_size` whose view scale is `view_scale`: top-left corner, or top-right when the
  // cursor is in the left half so it never covers the point being placed.
  static LoupeGeometry geometry(const QSize& canvas_size, const QPointF& cursor_widget,
                                const QPointF& image_point, double view_scale);

  static void paint(QPainter& painter, const LoupeGeometry& g, const QImage& display,
                    const QSize& photo_size);
};

}  // namespace artcam::ui
