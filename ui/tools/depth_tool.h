// SPDX-License-Identifier: Apache-2.0
// The depth tool, in one of four modes on the active depth layer:
// - Brush / Eraser: press and drag paints (erases) the layer's mask with the settings' radius
//   and hardness; the stroke paints live and becomes ONE undo command on release.
// - Polygon: each click adds a vertex; Enter or a click on the first vertex closes and fills it
//   (Alt held on closing erases instead), Backspace drops the last vertex, Esc drops them all.
// - Points: a click places the next of the layer's three depth points with the settings' next
//   depth; with three placed, a click replaces the nearest one; dragging a point moves it
//   (one undo step per drag). Depth values are edited in the depth panel.
// Painting with no layer creates one first (same undo macro as the first stroke).
// With the settings' edge-aware switch, a stroke paints only what its first pixel's colour
// reaches inside each dab (core/depth/edge_aware_brush.h). While the tool is active the
// active layer's mask is tinted (depth_mask_tint.h), so strokes show before the plane has its
// three depths.
// The tool works on the result too (canvas.h): masks, vertices and depth points are photo
// pixels, and a press over the result is the photo pixel the result shows there (the camera's
// inverse, Canvas::photoPixelAt), so depth is painted while the result and its effects stay on
// screen; the tint, the vertices and the points are drawn where the result shows them. A stroke
// maps its whole path through the camera it began under; a press where the result shows no
// photo pixel is refused with a status message, and a stroke's dabs there are skipped.
#pragma once

#include "core/depth/edge_aware_brush.h"
#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "ui/tools/depth_tool_settings.h"
#include "ui/tools/tool.h"

#include <QPointF>
#include <QPolygonF>

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

class DepthModel;
class ResultInverse;

class DepthTool : public Tool {
 public:
  static constexpr double kHitRadius = 9.0;  // widget pixels: grabs a depth point or vertex

  DepthTool(Canvas* canvas, Document* document, DepthToolSettings* settings, DepthToolMode mode);

  DepthToolMode mode() const { return mode_; }
  int polygonVertexCount() const { return static_cast<int>(polygon_.size()); }
  bool isStroking() const { return stroke_layer_ >= 0; }

  void mousePress(QMouseEvent* event) override;
  void mouseMove(QMouseEvent* event) override;
  void mouseRelease(QMouseEvent* event) override;
  bool keyPress(QKeyEvent* event) override;
  void paint(QPainter& painter) override;
  void cancel() override;
  QString name() const override;
  QCursor cursor() const override;
  // Depth points and polygon corners are placed precisely.
  bool wantsLoupe() const override {
    return mode_ == DepthToolMode::Points || mode_ == DepthToolMode::Polygon;
  }
  bool worksOnResult() const override { return true; }

 private:
  // The photo pixel under a widget point (through the stroke's inverse during a stroke); none,
  // with the refusal in the status bar when `say_why`.
  std::optional<Eigen::Vector2d> photoPoint(const QPointF& widget, bool say_why) const;
  // Where a photo pixel is drawn (the canvas's photo or result); off screen when nowhere.
  QPointF widgetPoint(const Eigen::Vector2d& photo_px) const;
  DepthModel* depth() const;
  int ensureLayer();  // the active layer, made if there is none
  BrushOptions brush() const;
  void finishStroke();
  PixelRect strokeDab(RegionMask* mask, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                      bool first);
  void paintActiveMask(QPainter& painter) const;
  void paintMaskOnResult(QPainter& painter, const RegionMask& mask) const;
  // A circle of `radius_px` photo pixels about the photo pixel under the cursor, as the result
  // shows it (widget points); none where the photo shows, or nothing maps.
  std::optional<QPolygonF> resultRing(double radius_px) const;
  void closePolygon(bool erase);
  void pressPoints(const QPointF& widget);
  std::optional<int> hitAnchor(const QPointF& widget) const;

  DepthToolSettings* settings_;
  DepthToolMode mode_;
  QPointF cursor_widget_;
  bool cursor_inside_ = false;
  // Brush stroke in progress.
  int stroke_layer_ = -1;
  RegionMask stroke_before_;
  PixelRect stroke_rect_;
  Eigen::Vector2d stroke_last_{0, 0};
  bool stroke_made_layer_ = false;
  std::optional<EdgeAwareOptions> stroke_edges_;  // edge-aware stroke: its reference colour
  std::shared_ptr<const ResultInverse> stroke_inverse_;  // the camera the stroke began under
  bool stroke_gap_ = false;  // the last move had no photo pixel: the next dab starts afresh
  // Polygon in progress (photo pixels).
  std::vector<Eigen::Vector2d> polygon_;
  // Depth point drag.
  int drag_anchor_ = -1;
  std::vector<DepthAnchor> drag_before_;
};

}  // namespace artcam::ui
