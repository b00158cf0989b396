// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/line_tool.h"

#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/line_commands.h"
#include "ui/tools/tool_cursor.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>

#include <cmath>

namespace artcam::ui {

int LineTool::next_gesture_id_ = 1;

namespace {

QString tr(const char* text) { return QCoreApplication::translate("LineTool", text); }

double distance(const QPointF& a, const QPointF& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

}  // namespace

LineTool::LineTool(Canvas* canvas, Document* document) : Tool(canvas, document) {}

int LineTool::selectedLine() const {
  return selected_ < static_cast<int>(document_->lines().size()) ? selected_ : -1;
}

std::optional<LineTool::Hit> LineTool::hitTest(const QPointF& widget) const {
  std::optional<Hit> best;
  double best_d = kHitRadius;
  const auto& lines = document_->lines();
  for (size_t i = 0; i < lines.size(); ++i)
    for (size_t k = 0; k < lines[i].points.size(); ++k) {
      const Eigen::Vector2d& p = lines[i].points[k];
      const double d = distance(canvas_->view().widgetFromImage(QPointF(p.x(), p.y())), widget);
      if (d <= best_d) {  // later lines are drawn on top, so they win ties
        best_d = d;
        best = Hit{static_cast<int>(i), static_cast<int>(k)};
      }
    }
  return best;
}

void LineTool::mousePress(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  press_widget_ = event->position();
  cursor_widget_ = press_widget_;
  // The second press of a double click ends the line its first press added a point to.
  if (event->type() == QEvent::MouseButtonDblClick && !document_->openLine().empty()) {
    endLine();
    return;
  }
  // While a line is being traced every click adds to it, even on another line's point.
  if (document_->openLine().empty()) {
    if (const std::optional<Hit> hit = hitTest(press_widget_)) {
      grabbed_ = *hit;
      grabbed_at_ = document_->lines()[static_cast<size_t>(hit->line)]
                        .points[static_cast<size_t>(hit->point)];
      selected_ = hit->line;
      gesture_ = Gesture::PressedPoint;
      canvas_->update();
      return;
    }
  }
  selected_ = -1;
  const QPointF p = canvas_->view().imageFromWidget(press_widget_);
  pushAddLinePoint(document_, {p.x(), p.y()});
}

void LineTool::mouseMove(QMouseEvent* event) {
  cursor_widget_ = event->position();
  if (gesture_ == Gesture::PressedPoint && distance(cursor_widget_, press_widget_) > kDragThreshold) {
    gesture_ = Gesture::Dragging;
    gesture_id_ = next_gesture_id_++;
  }
  if (gesture_ == Gesture::Dragging) {
    const QPointF d = canvas_->view().imageFromWidget(cursor_widget_) -
                      canvas_->view().imageFromWidget(press_widget_);
    pushMoveLinePoint(document_, grabbed_.line, grabbed_.point,
                      grabbed_at_ + Eigen::Vector2d(d.x(), d.y()), gesture_id_);
  } else if (gesture_ == Gesture::None) {
    // Tell the user what a press would do here: grab a point or add one.
    canvas_->setCursor(document_->openLine().empty() && hitTest(cursor_widget_) ? Qt::SizeAllCursor
                                                                              : cursor());
  }
  canvas_->update();
}

void LineTool::mouseRelease(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  gesture_ = Gesture::None;
  canvas_->update();
}

void LineTool::endLine() {
  const int n = static_cast<int>(document_->openLine().size());
  if (n == 0) return;
  if (!pushEndLine(document_))
    canvas_->showToolMessage(tr("A line needs at least %1 points; this one has %2. Click more "
                                "points along the edge, or Esc to drop it.")
                                 .arg(kMinLinePoints)
                                 .arg(n));
}

bool LineTool::keyPress(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_Return:
    case Qt::Key_Enter:
      if (document_->openLine().empty()) return false;
      endLine();
      return true;
    case Qt::Key_Escape:
      gesture_ = Gesture::None;
      return pushCancelLine(document_);
    case Qt::Key_Delete:
    case Qt::Key_Backspace:
      if (selectedLine() < 0) return false;
      pushDeleteLine(document_, selectedLine());
      selected_ = -1;
      return true;
    default:
      return false;
  }
}

void LineTool::paint(QPainter& painter) {
  const auto& open = document_->openLine();
  if (!open.empty()) {
    // The rubber segment from the last point to the cursor: where the next click continues.
    const Eigen::Vector2d& last = open.back();
    painter.setPen(QPen(QColor(255, 220, 0), 1.5, Qt::DashLine));
    painter.drawLine(canvas_->view().widgetFromImage(QPointF(last.x(), last.y())), cursor_widget_);
  }
  if (const int s = selectedLine(); s >= 0) {
    const auto& points = document_->lines()[static_cast<size_t>(s)].points;
    painter.setPen(QPen(QColor(80, 160, 255), 2.0));
    painter.setBrush(Qt::NoBrush);
    for (const Eigen::Vector2d& p : points)
      painter.drawEllipse(canvas_->view().widgetFromImage(QPointF(p.x(), p.y())), 6.0, 6.0);
  }
}

void LineTool::cancel() {
  // The open line is document state (an undo step per point): a tool switch keeps it, Esc drops
  // it. Only the gesture in flight is dropped here.
  gesture_ = Gesture::None;
  canvas_->update();
}

QString LineTool::name() const { return tr("Lines"); }
QCursor LineTool::cursor() const { return toolCursor(QStringLiteral("S")); }

}  // namespace artcam::ui
