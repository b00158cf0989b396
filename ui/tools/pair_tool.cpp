// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/pair_tool.h"

#include "ui/canvas.h"
#include "ui/tools/tool_cursor.h"
#include "ui/commands.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>

#include <cmath>

namespace artcam::ui {

int PairTool::next_gesture_id_ = 1;

namespace {

double distance(const QPointF& a, const QPointF& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

Eigen::Vector2d toEigen(const QPointF& p) { return {p.x(), p.y()}; }

}  // namespace

PairTool::PairTool(Canvas* canvas, Document* document) : Tool(canvas, document) {}

QPointF PairTool::imagePoint(const QPointF& widget) const {
  return canvas_->view().imageFromWidget(widget);
}

std::optional<PairTool::Hit> PairTool::hitTest(const QPointF& widget) const {
  std::optional<Hit> best;
  double best_d = kHitRadius;
  const auto& pairs = document_->pairs();
  // Later pairs are drawn on top, so they win ties.
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (Endpoint e : {Endpoint::Source, Endpoint::Target}) {
      const Eigen::Vector2d& p = e == Endpoint::Source ? pairs[i].source : pairs[i].target;
      const QPointF at = canvas_->view().widgetFromImage(QPointF(p.x(), p.y()));
      const double d = distance(at, widget);
      if (d <= best_d) {
        best_d = d;
        best = Hit{static_cast<int>(i), e};
      }
    }
  }
  return best;
}

void PairTool::mousePress(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  press_widget_ = event->position();
  cursor_widget_ = press_widget_;
  source_hint_at_.reset();
  shift_ = event->modifiers().testFlag(Qt::ShiftModifier);
  // While a source waits for its target every click places the target, even on a point.
  const std::optional<Hit> hit = pending_source_ ? std::nullopt : hitTest(press_widget_);
  if (!hit) {
    gesture_ = Gesture::PressedEmpty;
    return;
  }
  grabbed_ = *hit;
  if (shift_) {
    std::vector<int> sel = document_->selection();
    if (document_->isSelected(hit->index))
      std::erase(sel, hit->index);
    else
      sel.push_back(hit->index);
    document_->setSelection(sel);
    gesture_ = Gesture::None;
    return;
  }
  if (!document_->isSelected(hit->index)) document_->setSelection({hit->index});
  gesture_ = Gesture::PressedPoint;
}

void PairTool::mouseMove(QMouseEvent* event) {
  cursor_widget_ = event->position();
  switch (gesture_) {
    case Gesture::PressedEmpty:
      if (!pending_source_ && distance(cursor_widget_, press_widget_) > kDragThreshold)
        gesture_ = Gesture::RubberBand;
      break;
    case Gesture::PressedPoint:
      if (distance(cursor_widget_, press_widget_) > kDragThreshold) {
        gesture_ = Gesture::Dragging;
        gesture_id_ = next_gesture_id_++;
        drag_indices_ = document_->selection();
        drag_before_.clear();
        for (int i : drag_indices_)
          drag_before_.push_back(document_->pairs().at(static_cast<size_t>(i)));
        drag_inverse_.reset();
        drag_last_photo_.reset();
        if (grabbed_.endpoint == Endpoint::Source && !canvas_->photoVisibleAt(press_widget_)) {
          // Grabbed over the result: the cursor's motion is mapped back through this camera
          // for the whole drag. A press where the result shows no photo pixel moves the
          // sources by the cursor's motion in pixels, as on the photo.
          auto inverse = canvas_->resultInverse();
          if (const PhotoPoint at = canvas_->photoPixelAt(press_widget_, inverse.get()); at.pixel) {
            drag_inverse_ = std::move(inverse);
            drag_press_photo_ = *at.pixel;
            drag_last_photo_ = at.pixel;
          }
        }
        dragTo(cursor_widget_);
      }
      break;
    case Gesture::Dragging:
      dragTo(cursor_widget_);
      break;
    case Gesture::None:
      if (source_hint_at_ && distance(cursor_widget_, *source_hint_at_) > 60.0)
        source_hint_at_.reset();
      // Tell the user what a press would do here: grab a point or place one.
      canvas_->setCursor(!pending_source_ && hitTest(cursor_widget_) ? Qt::SizeAllCursor
                                                                     : Qt::CrossCursor);
      break;
    case Gesture::RubberBand:
      break;
  }
  canvas_->update();
}

void PairTool::dragTo(const QPointF& widget) {
  Eigen::Vector2d d = toEigen(imagePoint(widget) - imagePoint(press_widget_));
  if (drag_inverse_) {
    const PhotoPoint now =
        drag_inverse_->photoPixelOf(toEigen(imagePoint(widget)), drag_last_photo_);
    if (!now.pixel) return;  // off the photo: the sources stay where they last were
    drag_last_photo_ = now.pixel;
    d = *now.pixel - drag_press_photo_;
  }
  std::vector<Pair> after = drag_before_;
  for (Pair& p : after) (grabbed_.endpoint == Endpoint::Source ? p.source : p.target) += d;
  document_->undoStack()->push(
      new MovePairsCommand(document_, drag_indices_, drag_before_, std::move(after), gesture_id_,
                           QCoreApplication::translate("PairTool", "Move %n point(s)", nullptr,
                                                       static_cast<int>(drag_indices_.size()))));
}

void PairTool::mouseRelease(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  cursor_widget_ = event->position();
  const Gesture g = gesture_;
  gesture_ = Gesture::None;
  switch (g) {
    case Gesture::PressedEmpty: {
      const Eigen::Vector2d p = toEigen(imagePoint(cursor_widget_));
      if (!pending_source_) {
        document_->setSelection({});
        const PhotoPoint source = canvas_->photoPixelAt(cursor_widget_);
        if (source.pixel) {
          pending_source_ = source.pixel;
        } else {
          source_hint_at_ = cursor_widget_;
          source_hint_ = source.refusal;
          canvas_->showToolMessage(source.refusal);
        }
      } else {
        Pair pair;
        pair.source = *pending_source_;
        pair.target = p;
        pending_source_.reset();
        document_->undoStack()->push(new AddPairCommand(document_, pair));
      }
      break;
    }
    case Gesture::RubberBand: {
      const QRectF band = QRectF(press_widget_, cursor_widget_).normalized();
      std::vector<int> sel = shift_ ? document_->selection() : std::vector<int>{};
      const auto& pairs = document_->pairs();
      for (size_t i = 0; i < pairs.size(); ++i) {
        const QPointF s =
            canvas_->view().widgetFromImage(QPointF(pairs[i].source.x(), pairs[i].source.y()));
        const QPointF t =
            canvas_->view().widgetFromImage(QPointF(pairs[i].target.x(), pairs[i].target.y()));
        if (band.contains(s) || band.contains(t)) sel.push_back(static_cast<int>(i));
      }
      document_->setSelection(sel);
      break;
    }
    case Gesture::PressedPoint:
    case Gesture::Dragging:
    case Gesture::None:
      break;
  }
  drag_inverse_.reset();
  canvas_->update();
}

bool PairTool::keyPress(QKeyEvent* event) {
  if (event->key() == Qt::Key_Escape) {
    if (!pending_source_ && gesture_ == Gesture::None) return false;
    cancel();
    return true;
  }
  if (event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) {
    if (document_->selection().empty()) return false;
    pushDeleteSelection(document_);
    return true;
  }
  return false;
}

void PairTool::paint(QPainter& painter) {
  if (pending_source_) {
    const QPointF s =
        canvas_->view().widgetFromImage(QPointF(pending_source_->x(), pending_source_->y()));
    painter.setPen(QPen(QColor(255, 220, 0), 1.5, Qt::DashLine));
    painter.drawLine(s, cursor_widget_);
    painter.setPen(QPen(QColor(255, 220, 0), 2.0));
    painter.drawEllipse(s, 5.0, 5.0);
  }
  if (source_hint_at_) {
    const QString& hint = source_hint_;
    const QRectF box(*source_hint_at_ + QPointF(12, 8),
                     QSizeF(painter.fontMetrics().horizontalAdvance(hint) + 12,
                            painter.fontMetrics().height() + 6));
    painter.save();
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 170));
    painter.drawRoundedRect(box, 4, 4);
    painter.setPen(QColor(255, 220, 0));
    painter.drawText(box, Qt::AlignCenter, hint);
    painter.restore();
  }
  if (gesture_ == Gesture::RubberBand) {
    painter.setPen(QPen(QColor(80, 160, 255), 1.0, Qt::DashLine));
    painter.setBrush(QColor(80, 160, 255, 40));
    painter.drawRect(QRectF(press_widget_, cursor_widget_).normalized());
    painter.setBrush(Qt::NoBrush);
  }
}

void PairTool::cancel() {
  pending_source_.reset();
  source_hint_at_.reset();
  gesture_ = Gesture::None;
  drag_inverse_.reset();
  canvas_->update();
}

QString PairTool::name() const { return QCoreApplication::translate("PairTool", "Pairs"); }
QCursor PairTool::cursor() const { return toolCursor(QStringLiteral("P")); }

}  // namespace artcam::ui
