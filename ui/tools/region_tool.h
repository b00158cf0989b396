// SPDX-License-Identifier: Apache-2.0
// The region tool of Insertion mode: click the corners of a polygon around the reflecting or
// refracting object; Enter, a double click or a click on the first corner closes it and makes
// it the region (one undo step) — the composite is limited to it. Backspace drops the last
// corner, Esc the polygon being drawn, Del (with none being drawn) clears the region.
#pragma once

#include "ui/tools/tool.h"

#include <Eigen/Core>

#include <QPointF>

#include <vector>

namespace artcam::ui {

class InsertionModel;
class InsertionPreview;

class RegionTool : public Tool {
 public:
  static constexpr double kCloseRadius = 8.0;  // widget pixels around the first corner

  RegionTool(Canvas* canvas, Document* document, InsertionModel* model, InsertionPreview* preview);

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;

  const std::vector<Eigen::Vector2d>& pending() const { return pending_; }
  // Makes the pending polygon the region (when it has 3 corners or more).
  void close();

 private:
  InsertionModel* model_;
  InsertionPreview* preview_;
  std::vector<Eigen::Vector2d> pending_;  // photo pixels
  QPointF cursor_widget_;
};

}  // namespace artcam::ui
