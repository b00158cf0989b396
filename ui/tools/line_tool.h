// SPDX-License-Identifier: Apache-2.0
// The line tool, for lens calibration from straight edges (core/fit/fit_lines.h): click points
// along an edge that is straight in the scene; Enter or a double click ends the line (refused,
// with a message in the status bar, below 3 points), Esc drops the line being traced. A click on
// a point of a finished line selects that line, a drag moves the point (one merged undo step,
// fitted in the worker while it moves), Delete removes the selected line. Every edit is a
// SetLinesCommand (line_commands.h).
//
// Points are photo pixels (centres at i + 0.5): the tool edits the photo, so the canvas shows
// the photo while it is active (Tool::worksOnResult false); the lines, their bows and their
// mapped images on the result are drawn by the canvas in every mode (line_annotations.h).
#pragma once

#include "ui/tools/tool.h"

#include <Eigen/Core>

#include <QPointF>

#include <optional>

namespace artcam::ui {

class LineTool : public Tool {
 public:
  static constexpr double kHitRadius = 8.0;      // widget px within which a click grabs a point
  static constexpr double kDragThreshold = 4.0;  // widget px before a press is a drag

  LineTool(Canvas* canvas, Document* document);

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;
  bool wantsLoupe() const override { return gesture_ != Gesture::None; }

  // The selected finished line (view state, like the pair selection); -1: none.
  int selectedLine() const;
  // Ends the open line, or says in the status bar why not.
  void endLine();

 private:
  struct Hit {
    int line;
    int point;
  };
  enum class Gesture { None, PressedPoint, Dragging };

  std::optional<Hit> hitTest(const QPointF& widget) const;

  Gesture gesture_ = Gesture::None;
  QPointF press_widget_;
  QPointF cursor_widget_;
  Hit grabbed_{-1, -1};
  Eigen::Vector2d grabbed_at_{0.0, 0.0};  // the grabbed point's position at press time
  int selected_ = -1;
  int gesture_id_ = 0;
  static int next_gesture_id_;
};

}  // namespace artcam::ui
