// SPDX-License-Identifier: Apache-2.0
#include "ui/loupe.h"

#include <QPainter>
#include <QPen>

#include <algorithm>
#include <cmath>

namespace artcam::ui {

LoupeGeometry Loupe::geometry(const QSize& canvas_size, const QPointF& cursor_widget,
                              const QPointF& image_point, double view_scale) {
  LoupeGeometry g;
  const double side = std::min<double>(kSide, std::min(canvas_size.width(), canvas_size.height()) / 2.0);
  if (side < 32.0) return g;  // too small a canvas for a useful loupe
  const bool cursor_left = cursor_widget.x() < canvas_size.width() / 2.0;
  const double x = cursor_left ? canvas_size.width() - side - kMargin : kMargin;
  g.widget_rect = QRectF(x, kMargin, side, side);
  g.image_centre = image_point;
  g.scale = std::clamp(view_scale * kMagnification, kMinScale, kMaxScale);
  return g;
}

void Loupe::paint(QPainter& painter, const LoupeGeometry& g, const QImage& display,
                  const QSize& photo_size) {
  if (!g.isValid() || display.isNull() || photo_size.isEmpty()) return;
  painter.save();
  painter.setClipRect(g.widget_rect);
  painter.fillRect(g.widget_rect, QColor(30, 30, 34));
  // The photo placed so that image_centre lands on the loupe's centre, at g.scale: the same
  // mapping as LoupeGeometry::imageFromWidget. Nearest so pixels show as squares.
  const double sx = static_cast<double>(display.width()) / photo_size.width();
  const double sy = static_cast<double>(display.height()) / photo_size.height();
  const QPointF c = g.widget_rect.center();
  QTransform t;
  t.translate(c.x() - g.image_centre.x() * g.scale, c.y() - g.image_centre.y() * g.scale);
  t.scale(g.scale / sx, g.scale / sy);
  painter.setTransform(t, true);
  painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
  // Only the display pixels the loupe can show (drawImage of the whole picture would scale it all).
  const double half = g.widget_rect.width() / 2.0 / g.scale + 2.0;
  const QRect src = QRectF((g.image_centre.x() - half) * sx, (g.image_centre.y() - half) * sy,
                           2 * half * sx, 2 * half * sy)
                        .toAlignedRect()
                        .intersected(display.rect());
  if (!src.isEmpty()) painter.drawImage(QRectF(src), display, src);
  painter.restore();

  // Crosshair on the exact cursor position, with a gap so the pixel under it stays visible.
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);
  const double gap = std::max(4.0, g.scale * 0.6);
  for (const auto& [colour, width] : {std::pair{QColor(0, 0, 0, 200), 3.0},
                                      std::pair{QColor(255, 255, 255), 1.0}}) {
    painter.setPen(QPen(colour, width));
    painter.drawLine(QPointF(g.widget_rect.left(), c.y()), QPointF(c.x() - gap, c.y()));
    painter.drawLine(QPointF(c.x() + gap, c.y()), QPointF(g.widget_rect.right(), c.y()));
    painter.drawLine(QPointF(c.x(), g.widget_rect.top()), QPointF(c.x(), c.y() - gap));
    painter.drawLine(QPointF(c.x(), c.y() + gap), QPointF(c.x(), g.widget_rect.bottom()));
  }
  painter.setPen(QPen(QColor(200, 200, 200), 1.0));
  painter.setBrush(Qt::NoBrush);
  painter.drawRect(g.widget_rect);
  painter.drawText(g.widget_rect.adjusted(4, 2, -4, -2), Qt::AlignLeft | Qt::AlignBottom,
                   QStringLiteral("%1, %2").arg(g.image_centre.x(), 0, 'f', 2).arg(g.image_centre.y(), 0, 'f', 2));
  painter.restore();
}

}  // namespace artcam::ui
