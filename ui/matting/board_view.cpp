// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/board_view.h"

#include "ui/matting/insertion_model.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>

#include <algorithm>

namespace artcam::ui {

BoardView::BoardView(InsertionModel* model, QWidget* parent) : QWidget(parent), model_(model) {
  setFocusPolicy(Qt::ClickFocus);
  setMinimumSize(180, 180);
  setToolTip(
      tr("The canonical board: click a corner to choose which corner the next photo "
         "click matches (arrow keys move it)"));
  connect(model_, &InsertionModel::stateChanged, this, qOverload<>(&QWidget::update));
  connect(model_, &InsertionModel::selectionChanged, this, qOverload<>(&QWidget::update));
}

int BoardView::heightForWidth(int w) const {
  const FrameSize b = model_->state().board_size;
  return b.width > 0 ? w * b.height / b.width : w;
}

QRectF BoardView::boardRect() const {
  const FrameSize b = model_->state().board_size;
  const double margin = 6.0;
  const double avail_w = std::max(1.0, width() - 2 * margin);
  const double avail_h = std::max(1.0, height() - 2 * margin);
  const double s = std::min(avail_w / std::max(1, b.width), avail_h / std::max(1, b.height));
  const double w = b.width * s, h = b.height * s;
  return {(width() - w) / 2, (height() - h) / 2, w, h};
}

QPointF BoardView::widgetFromBoard(const QPointF& board) const {
  const QRectF r = boardRect();
  const FrameSize b = model_->state().board_size;
  return {r.left() + board.x() / std::max(1, b.width) * r.width(),
          r.top() + board.y() / std::max(1, b.height) * r.height()};
}

QPointF BoardView::boardFromWidget(const QPointF& widget) const {
  const QRectF r = boardRect();
  const FrameSize b = model_->state().board_size;
  return {(widget.x() - r.left()) / std::max(1.0, r.width()) * b.width,
          (widget.y() - r.top()) / std::max(1.0, r.height()) * b.height};
}

void BoardView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const QRectF r = boardRect();
  const int n = std::max(1, model_->state().squares);
  p.fillRect(rect(), palette().window());
  p.fillRect(r, QColor(235, 235, 235));
  const double cw = r.width() / n, ch = r.height() / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if ((i + j) % 2 == 0)
        p.fillRect(QRectF(r.left() + i * cw, r.top() + j * ch, cw, ch), QColor(60, 60, 60));
  p.setRenderHint(QPainter::Antialiasing, true);
  // Matched corners get a small filled dot; unmatched ones stay bare (the board's own
  // corners show them), so a dense board stays readable.
  const double dot = std::clamp(std::min(cw, ch) * 0.18, 0.8, 4.0);
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(255, 0, 200));
  // The click mode's kind only: the corners still to click on the table, or in the object.
  for (const GridMatch& m : model_->state().matches)
    if (m.on_table == model_->clickingTable())
      p.drawEllipse(widgetFromBoard(QPointF(m.board.x(), m.board.y())), dot, dot);
  const InsertionState& s = model_->state();
  if (s.graphic && !s.placement.fillsBoard() && s.graphic->width > 0) {
    const double h = s.placement.width * s.graphic->height / s.graphic->width;
    const QPointF a = widgetFromBoard(QPointF(s.placement.origin.x(), s.placement.origin.y()));
    const QPointF b = widgetFromBoard(
        QPointF(s.placement.origin.x() + s.placement.width, s.placement.origin.y() + h));
    p.setPen(QPen(QColor(0, 200, 255), 2.0, Qt::DashLine));
    p.setBrush(Qt::NoBrush);
    p.drawRect(QRectF(a, b));
  }
  if (model_->cornerCount() > 0) {
    const Eigen::Vector2d b = model_->cornerPosition(model_->selectedCorner());
    p.setPen(QPen(QColor(255, 220, 0), 2.0));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(widgetFromBoard(QPointF(b.x(), b.y())), dot + 3, dot + 3);
  }
}

void BoardView::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  const QPointF b = boardFromWidget(event->position());
  const FrameSize size = model_->state().board_size;
  const double tolerance =
      0.5 * std::max(size.width, size.height) / std::max(1, model_->state().squares);
  const int corner = model_->cornerAt({b.x(), b.y()}, tolerance);
  if (corner >= 0) {
    model_->setSelectedCorner(corner);
    model_->setSelectedMatch(model_->matchOfCorner(corner));
  }
}

void BoardView::keyPressEvent(QKeyEvent* event) {
  const int n = model_->cornersPerRow();
  int c = model_->selectedCorner();
  switch (event->key()) {
    case Qt::Key_Left:
      c -= 1;
      break;
    case Qt::Key_Right:
      c += 1;
      break;
    case Qt::Key_Up:
      c -= n;
      break;
    case Qt::Key_Down:
      c += n;
      break;
    default:
      QWidget::keyPressEvent(event);
      return;
  }
  if (c >= 0 && c < model_->cornerCount()) model_->setSelectedCorner(c);
}

}  // namespace artcam::ui
