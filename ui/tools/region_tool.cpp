// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/region_tool.h"

#include "ui/canvas.h"
#include "ui/tools/tool_cursor.h"
#include "ui/document.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_overlay.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPolygonF>

#include <cmath>

namespace artcam::ui {

RegionTool::RegionTool(Canvas* canvas, Document* document, InsertionModel* model,
                       InsertionPreview* preview)
    : Tool(canvas, document), model_(model), preview_(preview) {}

void RegionTool::mousePress(QMouseEvent* event) {
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

void RegionTool::mouseMove(QMouseEvent* event) {
  cursor_widget_ = event->position();
  if (!pending_.empty()) canvas_->update();
}

void RegionTool::mouseRelease(QMouseEvent*) {}

void RegionTool::close() {
  if (pending_.size() < 3) return;
  InsertionState next = model_->state();
  next.region = std::move(pending_);
  pending_.clear();
  model_->edit(next, QCoreApplication::translate("RegionTool", "Mark Region"));
  canvas_->update();
}

bool RegionTool::keyPress(QKeyEvent* event) {
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
    case Qt::Key_Delete:
      if (!pending_.empty() || model_->state().region.empty()) return false;
      {
        InsertionState next = model_->state();
        next.region.clear();
        model_->edit(next, QCoreApplication::translate("RegionTool", "Clear Region"));
      }
      canvas_->update();
      return true;
    default:
      return false;
  }
}

void RegionTool::paint(QPainter& painter) {
  InsertionOverlay::paint(painter, canvas_->view(), *model_, *preview_);
  if (pending_.empty()) return;
  QPolygonF line;
  for (const Eigen::Vector2d& p : pending_)
    line << canvas_->view().widgetFromImage(QPointF(p.x(), p.y()));
  line << cursor_widget_;
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.setPen(QPen(QColor(0, 200, 255), 1.5));
  painter.drawPolyline(line);
  for (int i = 0; i + 1 < line.size(); ++i) painter.drawEllipse(line[i], 3.0, 3.0);
  painter.restore();
}

void RegionTool::cancel() { pending_.clear(); }

QString RegionTool::name() const { return QCoreApplication::translate("RegionTool", "Insertion region"); }
QCursor RegionTool::cursor() const { return toolCursor(QStringLiteral("R")); }

}  // namespace artcam::ui
