// SPDX-License-Identifier: Apache-2.0
// The grid tool of Insertion mode: a click in the photo places the match of the board corner
// selected in the board view (ui/matting/board_view.h). The click is snapped to the nearest
// checkerboard X-corner (core/piecewise/corner_snap.h; Shift-click: no snap), becomes one undo
// step, and the board's selection advances along the row. A click on an existing match
// selects it (and its corner); Del / Backspace remove the selected match; Esc clears the
// selection. Paints the Insertion overlay (composite, error map, region, matches).
#pragma once

#include "core/model/image.h"
#include "ui/tools/tool.h"

#include <Eigen/Core>

#include <QPointF>

#include <functional>
#include <optional>

namespace artcam::ui {

class InsertionModel;
class InsertionPreview;

// Sub-pixel corner within search_radius_px of a click (photo pixels), or empty when there is
// none.
using CornerSnapper = std::function<std::optional<Eigen::Vector2d>(
    const ImageF& photo, const Eigen::Vector2d& click, double search_radius_px)>;

class GridTool : public Tool {
 public:
  static constexpr double kHitRadius = 5.0;  // widget pixels that select an existing match
  // How far (widget pixels) a click may be from the corner it means: the snap's search radius
  // is this over the zoom, so zooming in picks one of densely packed reflected corners.
  static constexpr double kSnapRadiusWidgetPx = 5.0;

  GridTool(Canvas* canvas, Document* document, InsertionModel* model, InsertionPreview* preview,
           CornerSnapper snapper);

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;
  bool wantsLoupe() const override { return dragging_; }

  // Places the selected corner's match at a photo point (snapped within search_radius_px
  // unless it is 0); returns the point used. What a click does, callable without events.
  Eigen::Vector2d placeAt(const Eigen::Vector2d& photo_px, double search_radius_px);

 private:
  int hitTest(const QPointF& widget) const;
  double searchRadius(Qt::KeyboardModifiers modifiers) const;

  InsertionModel* model_;
  InsertionPreview* preview_;
  CornerSnapper snapper_;
  int pressed_match_ = -1;  // the match under the press, while the button is down
  bool dragging_ = false;
  QPointF press_widget_;
  QPointF drag_widget_;
};

}  // namespace artcam::ui
