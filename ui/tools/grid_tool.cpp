// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/grid_tool.h"

#include "ui/canvas.h"
#include "ui/tools/tool_cursor.h"
#include "ui/document.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_overlay.h"
#include "ui/matting/insertion_preview.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPen>

#include <cmath>

namespace artcam::ui {

GridTool::GridTool(Canvas* canvas, Document* document, InsertionModel* model,
                   InsertionPreview* preview, CornerSnapper snapper)
    : Tool(canvas, document), model_(model), preview_(preview), snapper_(std::move(snapper)) {}

int GridTool::hitTest(const QPointF& widget) const {
  const auto& matches = model_->state().matches;
  int best = -1;
  double best_d = kHitRadius;
  for (size_t k = 0; k < matches.size(); ++k) {
    const QPointF w =
        canvas_->view().widgetFromImage(QPointF(matches[k].photo.x(), matches[k].photo.y()));
    const double d = std::hypot(w.x() - widget.x(), w.y() - widget.y());
    if (d <= best_d) {
      best_d = d;
      best = static_cast<int>(k);
    }
  }
  return best;
}

Eigen::Vector2d GridTool::placeAt(const Eigen::Vector2d& photo_px, double search_radius_px) {
  Eigen::Vector2d p = photo_px;
  const PhotoPtr& photo = document_->photo();
  // Snapping reads full-resolution pixels: a first look (no full image yet) places unsnapped.
  if (search_radius_px > 0.0 && snapper_ && photo && photo->hasFullImage())
    if (const auto snapped = snapper_(photo->full.image, photo_px, search_radius_px)) p = *snapped;
  if (model_->cornerCount() <= 0) return p;
  const int corner = model_->selectedCorner();
  InsertionState next = model_->state();
  const GridMatch match{model_->cornerPosition(corner), p, model_->clickingTable()};
  int index = model_->matchOfCorner(corner);
  if (index >= 0) {
    next.matches[static_cast<size_t>(index)] = match;
  } else {
    next.matches.push_back(match);
    index = static_cast<int>(next.matches.size()) - 1;
  }
  model_->edit(next, QCoreApplication::translate("GridTool", "Place Grid Corner"));
  model_->setSelectedMatch(index);
  // Advance along the row (row-major, so the row's end continues on the next row).
  if (corner + 1 < model_->cornerCount()) model_->setSelectedCorner(corner + 1);
  return p;
}

double GridTool::searchRadius(Qt::KeyboardModifiers modifiers) const {
  return (modifiers & Qt::ShiftModifier) ? 0.0 : kSnapRadiusWidgetPx / canvas_->view().scale();
}

void GridTool::mousePress(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !document_->photo()) return;
  const int hit = hitTest(event->position());
  pressed_match_ = hit;
  dragging_ = false;
  press_widget_ = drag_widget_ = event->position();
  if (hit >= 0) {
    model_->setSelectedMatch(hit);
    const int corner =
        model_->cornerAt(model_->state().matches[static_cast<size_t>(hit)].board, 1e-6);
    if (corner >= 0) model_->setSelectedCorner(corner);
  } else {
    const QPointF image = canvas_->view().imageFromWidget(event->position());
    placeAt({image.x(), image.y()}, searchRadius(event->modifiers()));
  }
  canvas_->update();
}

void GridTool::mouseMove(QMouseEvent* event) {
  if (pressed_match_ < 0 || !(event->buttons() & Qt::LeftButton)) return;
  drag_widget_ = event->position();
  const QPointF d = drag_widget_ - press_widget_;
  if (!dragging_ && std::hypot(d.x(), d.y()) >= 3.0) dragging_ = true;
  if (dragging_) canvas_->update();
}

void GridTool::mouseRelease(QMouseEvent* event) {
  const int k = pressed_match_;
  const bool moved = dragging_;
  pressed_match_ = -1;
  dragging_ = false;
  if (!moved || k < 0 || k >= static_cast<int>(model_->state().matches.size())) return;
  const QPointF image = canvas_->view().imageFromWidget(event->position());
  Eigen::Vector2d p(image.x(), image.y());
  const double radius = searchRadius(event->modifiers());
  if (radius > 0.0 && snapper_ && document_->photo() && document_->photo()->hasFullImage())
    if (const auto snapped = snapper_(document_->photo()->full.image, p, radius)) p = *snapped;
  InsertionState next = model_->state();
  next.matches[static_cast<size_t>(k)].photo = p;
  model_->edit(next, QCoreApplication::translate("GridTool", "Move Grid Match"));
  canvas_->update();
}

bool GridTool::keyPress(QKeyEvent* event) {
  if (event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) {
    const int k = model_->selectedMatch();
    if (k < 0) return false;
    InsertionState next = model_->state();
    next.matches.erase(next.matches.begin() + k);
    model_->setSelectedMatch(-1);
    model_->edit(next, QCoreApplication::translate("GridTool", "Delete Grid Match"));
    canvas_->update();
    return true;
  }
  if (event->key() == Qt::Key_Escape) {
    model_->setSelectedMatch(-1);
    canvas_->update();
    return true;
  }
  return false;
}

void GridTool::paint(QPainter& painter) {
  InsertionOverlay::paint(painter, canvas_->view(), *model_, *preview_);
  if (!dragging_) return;
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.setPen(QPen(QColor(255, 255, 0), 1.5));
  painter.setBrush(Qt::NoBrush);
  painter.drawEllipse(drag_widget_, 6.0, 6.0);
  painter.restore();
}

void GridTool::cancel() {
  pressed_match_ = -1;
  dragging_ = false;
  model_->setSelectedMatch(-1);
}

QString GridTool::name() const { return QCoreApplication::translate("GridTool", "Grid corners"); }
QCursor GridTool::cursor() const { return toolCursor(QStringLiteral("C")); }

}  // namespace artcam::ui
