// SPDX-License-Identifier: Apache-2.0
#include "ui/grid_overlay.h"

#include <QLineF>
#include <QPainter>
#include <QPen>

#include <vector>

namespace artcam::ui {

namespace {

void drawLines(QPainter& painter, const std::vector<QLineF>& lines, int alpha) {
  painter.setPen(QPen(QColor(0, 0, 0, alpha), 3.0));
  for (const QLineF& l : lines) painter.drawLine(l);
  painter.setPen(QPen(QColor(255, 255, 255, alpha), 1.0));
  for (const QLineF& l : lines) painter.drawLine(l);
}

std::vector<QLineF> divisions(const QRectF& r, int parts) {
  std::vector<QLineF> lines;
  for (int k = 1; k < parts; ++k) {
    const double x = r.left() + r.width() * k / parts;
    const double y = r.top() + r.height() * k / parts;
    lines.emplace_back(x, r.top(), x, r.bottom());
    lines.emplace_back(r.left(), y, r.right(), y);
  }
  return lines;
}

}  // namespace

void paintGridOverlay(QPainter& painter, const QRectF& r, const GridOverlayOptions& options) {
  if (r.isEmpty()) return;
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);  // crisp one-pixel lines
  painter.setClipRect(r, Qt::IntersectClip);
  if (options.divisions > 1) drawLines(painter, divisions(r, options.divisions), 70);
  if (options.thirds) drawLines(painter, divisions(r, 3), 170);
  painter.restore();
}

}  // namespace artcam::ui
