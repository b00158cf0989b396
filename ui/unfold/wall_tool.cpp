// SPDX-License-Identifier: Apache-2.0
#include "ui/unfold/wall_tool.h"

#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/tools/tool_cursor.h"
#include "ui/unfold/walls_model.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPolygonF>

#include <cmath>

namespace artcam::ui {
WallTool::WallTool(Canvas* canvas, Document* document, WallsModel* model)
    : Tool(canvas, document), model_(model) {}

void WallTool::mousePress(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !document_->photo()) return;
  if (pending_.size() >= 3) {
    const QPointF first =
        canvas_->view().widgetFromImage(QPointF(pending_[0].x(), pending_[0].y()));
    if (std::hypot(first.x() - event->position().x(), first.y() - event->position().y()) <=
        kCloseRadius) {
      close();
      return;
    }
  }
  if (event->type() == QEvent::MouseButtonDblClick) {
    close();
    return;
  }
  const QPointF p = canvas_->view().imageFromWidget(event->position());
  pending_.push_back({p.x(), p.y()});
  canvas_->update();
}

void WallTool::mouseMove(QMouseEvent* event) {
  cursor_widget_ = event->position();
  if (!pending_.empty()) canvas_->update();
}

void WallTool::mouseRelease(QMouseEvent*) {}

void WallTool::close() {
  if (pending_.size() < 3) return;
  model_->addWall(std::move(pending_));
  pending_.clear();
  canvas_->update();
}

bool WallTool::keyPress(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_Return:
    case Qt::Key_Enter:
      close();
      return true;
    case Qt::Key_Escape:
      pending_.clear();
      canvas_->update();
      return true;
    case Qt::Key_Backspace:
      if (pending_.empty()) return false;
      pending_.pop_back();
      canvas_->update();
      return true;
    case Qt::Key_Delete: {
      if (!pending_.empty()) return false;
      const QPointF p = canvas_->view().imageFromWidget(cursor_widget_);
      std::vector<WallOutline> next = model_->walls();
      for (auto it = next.begin(); it != next.end(); ++it)
        if (insideOutline(it->photo_px, {p.x(), p.y()})) {
          next.erase(it);
          model_->edit(std::move(next), QCoreApplication::translate("WallTool", "Remove Wall"));
          canvas_->update();
          return true;
        }
      return false;
    }
    default:
      return false;
  }
}

void WallTool::paint(QPainter& painter) {
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  const ViewTransform& view = canvas_->view();
  auto widget = [&](const Eigen::Vector2d& p) {
    return view.widgetFromImage(QPointF(p.x(), p.y()));
  };
  int number = 1;
  for (const WallOutline& w : model_->walls()) {
    QPolygonF outline;
    for (const Eigen::Vector2d& p : w.photo_px) outline << widget(p);
    painter.setPen(QPen(QColor(255, 200, 0), 1.5));
    painter.setBrush(QColor(255, 200, 0, 40));
    painter.drawPolygon(outline);
    painter.setPen(QPen(QColor(255, 200, 0), 4.0));
    painter.drawLine(outline[0], outline[1]);  // the base
    QPointF centre(0, 0);
    for (const QPointF& q : outline) centre += q / outline.size();
    painter.setPen(Qt::black);
    const QString label = QStringLiteral("%1 %2").arg(number++).arg(QString::fromStdString(w.name));
    const QRectF box = painter.fontMetrics().boundingRect(label).adjusted(-3, -2, 3, 2);
    painter.fillRect(box.translated(centre - box.center()), QColor(255, 200, 0, 220));
    painter.drawText(box.translated(centre - box.center()), Qt::AlignCenter, label);
  }
  if (!pending_.empty()) {
    QPolygonF line;
    for (const Eigen::Vector2d& p : pending_) line << widget(p);
    line << cursor_widget_;
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(QColor(255, 200, 0), 1.5));
    painter.drawPolyline(line);
    for (int i = 0; i + 1 < line.size(); ++i) painter.drawEllipse(line[i], 3.0, 3.0);
  }
  painter.restore();
}

void WallTool::cancel() { pending_.clear(); }

QString WallTool::name() const { return QCoreApplication::translate("WallTool", "Walls"); }
QCursor WallTool::cursor() const { return toolCursor(QStringLiteral("W")); }

}  // namespace artcam::ui
