// SPDX-License-Identifier: Apache-2.0
// The pair tool: click a source point, then its target, to add a pair. On existing points:
// click selects (Shift toggles), drag moves the grabbed endpoint of every selected pair (one
// merged undo step per drag), a drag on empty space selects with a rubber band, Delete removes
// the selection, Escape drops a half-made pair.
//
// Over the warped result (Result, right of the Split divider) a source is the photo pixel the
// result shows where it is clicked (Canvas::photoPixelAt: the camera's inverse), so a whole pair
// is placed where the user looks; a click where the result shows no photo pixel places nothing
// and the status bar says why. A source dragged over the result moves by the cursor's motion
// mapped back through the camera as it was when the drag began: the drag's own moves refit the
// camera, and mapping through each new one would feed the source's motion back into itself.
#pragma once

#include "ui/document.h"
#include "ui/tools/tool.h"

#include <QPointF>
#include <QString>

#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

class ResultInverse;

class PairTool : public Tool {
 public:
  // Widget pixels within which a click grabs an endpoint.
  static constexpr double kHitRadius = 8.0;
  // Widget pixels a press must travel before it is a drag rather than a click.
  static constexpr double kDragThreshold = 4.0;

  PairTool(Canvas* canvas, Document* document);

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;
  // Placing a target, pressing to place or drag, or dragging.
  bool wantsLoupe() const override {
    return pending_source_.has_value() || gesture_ == Gesture::PressedEmpty ||
           gesture_ == Gesture::PressedPoint || gesture_ == Gesture::Dragging;
  }

  bool worksOnResult() const override { return true; }

  bool hasPendingSource() const { return pending_source_.has_value(); }

 private:
  struct Hit {
    int index;
    Endpoint endpoint;
  };
  enum class Gesture { None, PressedEmpty, PressedPoint, Dragging, RubberBand };

  std::optional<Hit> hitTest(const QPointF& widget) const;
  QPointF imagePoint(const QPointF& widget) const;
  void dragTo(const QPointF& widget);

  Gesture gesture_ = Gesture::None;
  QPointF press_widget_;
  QPointF cursor_widget_;
  bool shift_ = false;
  std::optional<Eigen::Vector2d> pending_source_;
  std::optional<QPointF> source_hint_at_;  // widget point of a refused source click
  QString source_hint_;                    // and why it was refused
  // Dragging state: grabbed endpoint, the pairs moved and their values at press time.
  Hit grabbed_{-1, Endpoint::Source};
  std::vector<int> drag_indices_;
  std::vector<Pair> drag_before_;
  // A source drag over the result: the inverse it began with, the photo pixel under the press,
  // and the last photo pixel under the cursor (the next solve's start).
  std::shared_ptr<const ResultInverse> drag_inverse_;
  Eigen::Vector2d drag_press_photo_{0, 0};
  std::optional<Eigen::Vector2d> drag_last_photo_;
  int gesture_id_ = 0;  // merges the MovePairsCommands of one drag
  static int next_gesture_id_;
};

}  // namespace artcam::ui
