// SPDX-License-Identifier: Apache-2.0
// The wall tool (Unfold menu, W): click a wall's corners in the photo; Enter, a double click
// or a click on the first corner closes the outline and adds it as a wall (one undo step; its
// base and place among the walls are found, walls_model.h). Backspace drops the last corner,
// Esc the outline being drawn, Del (with none being drawn) removes the wall under the cursor.
// Every wall is drawn while the tool is active, numbered left to right, its base thicker.
#pragma once

#include "ui/tools/tool.h"

#include <Eigen/Core>

#include <QPointF>

#include <vector>

namespace artcam::ui {

class WallsModel;

class WallTool : public Tool {
 public:
  static constexpr double kCloseRadius = 8.0;  // widget pixels around the first corner

  WallTool(Canvas* canvas, Document* document, WallsModel* model);

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;

  const std::vector<Eigen::Vector2d>& pending() const { return pending_; }
  // Adds the pending outline as a wall (when it has 3 corners or more).
  void close();

 private:
  WallsModel* model_;
  std::vector<Eigen::Vector2d> pending_;  // photo pixels
  QPointF cursor_widget_;
};

}  // namespace artcam::ui
