// SPDX-License-Identifier: Apache-2.0
// The editing canvas: paints the photo and the pairs (arrows source → target, coloured by
// residual green → red), owns the view transform (zoom, pan) and forwards every other pointer
// and key event to the active tool.
//
// Pan: middle drag, or space + left drag. Zoom: wheel (about the cursor), pinch (native zoom
// gestures of touchpads, QPinchGesture on touch screens, both about the gesture's centre),
// zoomToFit (Ctrl+0), zoomActual (Ctrl+1), zoomIn/zoomOut (Ctrl+= / Ctrl+-). Until the user
// zooms or pans, the view refits on resize. While the tool places or drags a point the loupe
// (loupe.h) magnifies the photo around the cursor.
#pragma once

#include "ui/loupe.h"
#include "ui/scaled_image_cache.h"
#include "ui/view_transform.h"

#include <QPoint>
#include <QWidget>

#include <memory>

namespace artcam::ui {

class DepthOverlay;
class Document;
class Tool;

class Canvas : public QWidget {
  Q_OBJECT

 public:
  explicit Canvas(Document* document, QWidget* parent = nullptr);
  ~Canvas() override;

  Document* document() const { return document_; }
  const ViewTransform& view() const { return view_; }
  void setTool(std::unique_ptr<Tool> tool);
  Tool* tool() const { return tool_.get(); }
  // Space held: a left drag pans. Set by the canvas's own keys and, while the pointer is over
  // the canvas, by SpacePanFilter (space_pan.h) whatever widget has the focus.
  void setSpacePan(bool down);
  bool isSpacePanning() const { return space_down_; }
  // The pointer is over the canvas (it tracks moves; cleared when the pointer leaves).
  bool isPointerInside() const { return cursor_inside_ || underMouse(); }
  // Draws the depth overlay (when visible) over the photo, with its legend.
  void setDepthOverlay(DepthOverlay* overlay);

  // Residual (px) drawn fully red; below it the arrow blends from green.
  static constexpr double kRedResidualPx = 4.0;
  static QColor residualColour(double residual_px);
  // Pair markers while the camera is set by hand (not fitted to them): a neutral light blue,
  // neither the residual ramp nor the grey of disabled pairs.
  static inline const QColor kUnfittedPairColour{150, 190, 230};

  bool isLoupeEnabled() const { return loupe_enabled_; }
  bool isGridVisible() const { return grid_visible_; }
  bool areResidualsMagnified() const { return residuals_magnified_; }
  // The loupe as it is drawn now (invalid when hidden).
  LoupeGeometry loupe() const;

 public slots:
  void zoomToFit();
  void zoomActual();
  void zoomIn();
  void zoomOut();
  // Restores a saved view (scale and image point at the centre).
  void setView(double scale, const QPointF& image_centre);
  void setLoupeEnabled(bool enabled);
  // Guides over the picture (grid_overlay.h).
  void setGridVisible(bool visible);
  // The residual vectors from fitted to clicked targets, ×10 (canvas_annotations.h).
  void setResidualsMagnified(bool magnified);

 signals:
  void viewChanged();
  void toolChanged();  // setTool made another tool active
  void cursorMoved(const QPointF& image_point);

 protected:
  bool event(QEvent* event) override;
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void keyReleaseEvent(QKeyEvent* event) override;
  void leaveEvent(QEvent* event) override;

 private:
  void onPhotoChanged();
  void applyCursor();  // pan hand while panning or Space is held, else the tool's cursor
  void paintPairs(QPainter& painter);
  void paintDepth(QPainter& painter, const QRectF& image_rect);
  void paintResidualAids(QPainter& painter);  // the legend and magnified residuals
  void userMovedView();
  void pinchBy(double factor, const QPointF& widget_centre);

  Document* document_;
  ViewTransform view_;
  ScaledImageCache display_cache_;  // the display copy at the current zoom
  std::unique_ptr<Tool> tool_;
  DepthOverlay* depth_overlay_ = nullptr;
  bool follow_fit_ = true;  // refit on resize until the user zooms or pans
  bool space_down_ = false;
  bool loupe_enabled_ = true;
  bool grid_visible_ = false;
  bool residuals_magnified_ = false;
  bool cursor_inside_ = false;
  QPointF cursor_widget_;
  bool panning_ = false;
  QPoint pan_last_;
};

}  // namespace artcam::ui
