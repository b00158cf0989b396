// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/patch_view.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace artcam::ui {

PatchView::PatchView(QString placeholder, QWidget* parent)
    : QWidget(parent), placeholder_(std::move(placeholder)) {
  setMinimumSize(120, 90);
  setMouseTracking(false);
  setFocusPolicy(Qt::ClickFocus);
}

void PatchView::setPhoto(QImage display, FrameSize photo_px) {
  display_ = std::move(display);
  photo_px_ = photo_px;
  update();
}

void PatchView::setMarks(std::vector<PatchMark> marks, int radius) {
  marks_ = std::move(marks);
  radius_ = radius;
  update();
}

QRectF PatchView::imageRect() const {
  if (!hasPhoto()) return {};
  const double s = scale();
  const double w = photo_px_.width * s, h = photo_px_.height * s;
  return {(width() - w) / 2.0, (height() - h) / 2.0, w, h};
}

double PatchView::scale() const {
  if (!photo_px_.isImage()) return 1.0;
  return std::min(width() / static_cast<double>(photo_px_.width),
                  height() / static_cast<double>(photo_px_.height));
}

QPointF PatchView::widgetFromPhoto(const Eigen::Vector2d& p) const {
  const QRectF r = imageRect();
  return {r.left() + p.x() * scale(), r.top() + p.y() * scale()};
}

Eigen::Vector2d PatchView::photoFromWidget(const QPointF& w) const {
  const QRectF r = imageRect();
  return {(w.x() - r.left()) / scale(), (w.y() - r.top()) / scale()};
}

int PatchView::markAt(const QPointF& widget) const {
  const double half = std::max(3.0, (radius_ + 0.5) * scale());
  for (int i = static_cast<int>(marks_.size()) - 1; i >= 0; --i) {
    const QPointF c = widgetFromPhoto(marks_[static_cast<size_t>(i)].centre);
    if (std::abs(widget.x() - c.x()) <= half && std::abs(widget.y() - c.y()) <= half) return i;
  }
  return -1;
}

void PatchView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), palette().window());
  if (!hasPhoto()) {
    p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, placeholder_);
    return;
  }
  p.setRenderHint(QPainter::SmoothPixmapTransform);
  p.drawImage(imageRect(), display_);
  p.setRenderHint(QPainter::Antialiasing);
  // The square covers whole pixels: the one under the point ± radius.
  const double side = (2 * radius_ + 1) * scale();
  for (const PatchMark& m : marks_) {
    const Eigen::Vector2d corner(std::floor(m.centre.x()) - radius_,
                                 std::floor(m.centre.y()) - radius_);
    const QPointF tl = widgetFromPhoto(corner);
    QRectF square(tl, QSizeF(side, side));
    if (square.width() < 5) square = QRectF(square.center() - QPointF(2.5, 2.5), QSizeF(5, 5));
    const QColor colour = m.pending    ? QColor(255, 200, 0)
                          : m.selected ? QColor(0, 170, 255)
                          : m.enabled  ? QColor(255, 255, 255)
                                       : QColor(150, 150, 150);
    p.setPen(QPen(Qt::black, 3));
    p.drawRect(square);
    p.setPen(QPen(colour, m.selected ? 2 : 1.5, m.enabled ? Qt::SolidLine : Qt::DashLine));
    p.drawRect(square);
    if (m.number > 0) {
      p.setPen(Qt::black);
      p.drawText(square.topRight() + QPointF(3, 1), QString::number(m.number));
      p.setPen(colour);
      p.drawText(square.topRight() + QPointF(2, 0), QString::number(m.number));
    }
  }
}

void PatchView::mousePressEvent(QMouseEvent* event) {
  if (!hasPhoto() || event->button() != Qt::LeftButton) return;
  const QPointF pos = event->position();
  if (!imageRect().contains(pos)) return;
  const int mark = markAt(pos);
  dragging_ = true;
  if (mark >= 0)
    emit pressedMark(mark);
  else
    emit pressedEmpty(photoFromWidget(pos));
}

void PatchView::mouseMoveEvent(QMouseEvent* event) {
  if (!dragging_ || !(event->buttons() & Qt::LeftButton)) return;
  const QRectF r = imageRect();
  const QPointF pos(std::clamp(event->position().x(), r.left(), r.right() - 1e-6),
                    std::clamp(event->position().y(), r.top(), r.bottom() - 1e-6));
  emit draggedTo(photoFromWidget(pos));
}

void PatchView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !dragging_) return;
  dragging_ = false;
  emit released();
}

}  // namespace artcam::ui
