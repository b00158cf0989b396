// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/tool_cursor.h"

#include <QFont>
#include <QPainter>
#include <QPainterPath>
#include <QPixmap>

namespace artcam::ui {

QCursor toolCursor(const QString& tag) {
  constexpr int kSize = 32, kHot = 10;
  QPixmap pixmap(kSize, kSize);
  pixmap.fill(Qt::transparent);
  QPainter p(&pixmap);
  p.setRenderHint(QPainter::Antialiasing, false);
  // A gapped crosshair, dark under light so it reads on any photo.
  const auto cross = [&p](const QColor& colour, int width) {
    p.setPen(QPen(colour, width));
    p.drawLine(kHot, 0, kHot, kHot - 3);
    p.drawLine(kHot, kHot + 3, kHot, 2 * kHot);
    p.drawLine(0, kHot, kHot - 3, kHot);
    p.drawLine(kHot + 3, kHot, 2 * kHot, kHot);
  };
  cross(Qt::black, 3);
  cross(Qt::white, 1);
  QFont font = p.font();
  font.setPixelSize(11);
  font.setBold(true);
  QPainterPath text;
  text.addText(QPointF(kHot + 6, kSize - 3), font, tag);
  p.setRenderHint(QPainter::Antialiasing, true);
  p.strokePath(text, QPen(Qt::black, 3));
  p.fillPath(text, Qt::white);
  p.end();
  return QCursor(pixmap, kHot, kHot);
}

}  // namespace artcam::ui
