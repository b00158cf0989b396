// SPDX-License-Identifier: Apache-2.0
// The editing canvas: paints the photo and the pairs (arrows source → target, coloured by
// residual green → red), owns the view transform (zoom, pan) and forwards every other pointer
// and key event to the active tool.
//
// Pan: middle drag, or space + left drag. Zoom: wheel (about the cursor), pinch (native zoom
// gestures of touchpads, QPinchGesture on touch screens, both about the gesture's centre),
// zoomToFit (Ctrl+0), zoomActual (Ctrl+1), zoomIn/zoomOut (Ctrl+= / Ctrl+-). Until the user
// zooms or pans, the view refits on resize. While the tool places or drags a point the loupe
// (loupe.h) magnifies the picture under the cursor.
//
// Photo and result (canvas_view_mode.h). Given a PreviewController (setPreview) the canvas shows
// that controller's image, the one the preview worker renders (there is no second renderer), as
// Photo, Result, Split (a wipe: photo left of a vertical divider, result right; drag the handle
// on the divider, or Alt+drag anywhere) or Onion (the result over the photo at an opacity). The
// result is in the target frame, which is the photo's frame for studio documents, so it is drawn
// into the photo's image rectangle (scaled up when the preview is smaller than the photo).
// Decisions:
// - Result is the default: the warped photo is what is being made; `\` flips to the photo.
// - Pairs are drawn the same in every mode: each arrow runs from where the feature is in the
//   photo (source) to where it is asked to be in the result (target). Nothing jumps on `\`.
// - Edit where you look (as Puppet Warp and Liquify do). Targets are result pixels: they are
//   placed, grabbed and dragged everywhere. Sources are photo pixels: where the photo shows
//   (Photo, Onion, left of the divider) a click is the photo pixel under it; over the result it
//   is the photo pixel the result shows there, the click mapped back through the inverse of the
//   camera the result shows (result_inverse.h). A point of the result with no photo pixel under
//   it (beyond a pole, outside the photo) is refused with a status message. So a whole pair is
//   placed on the result, a source click then its target click.
// - Depth tools paint the photo's masks through the same inverse: a stroke on the result lands
//   on the photo pixels the result shows under it, and the result, with its effects (haze, depth
//   of field), stays on screen while painting; the active mask's tint is drawn warped with it.
//   Tools that still edit the photo in its own frame (lines, insertion's grid and region) report
//   Tool::worksOnResult false: while one is active the canvas shows the photo whatever the mode;
//   the mode returns with the next tool that works on the result.
// - The result shown is always the newest the controller delivered for THIS photo, even while
//   a newer render is in flight (a badge says "updating"); before the first one arrives the
//   canvas shows a checkerboard and says so, never the photo in the result's place.
// - The depth overlay (photo pixels, colour by depth) is drawn only where the photo shows.
// - A canvas without a controller shows the photo only (tests of the tools, other uses).
#pragma once

#include "ui/canvas_view_mode.h"
#include "ui/loupe.h"
#include "ui/result_inverse.h"
#include "ui/scaled_image_cache.h"
#include "ui/view_transform.h"

#include <QPoint>
#include <QWidget>

#include <memory>
#include <optional>

namespace artcam::ui {

class DepthOverlay;
class Document;
class PreviewController;
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
  // The source of the result picture (see the top of this file); null: photo only.
  void setPreview(PreviewController* preview);
  PreviewController* preview() const { return preview_; }

  const CanvasViewState& viewState() const { return view_state_; }
  CanvasViewMode viewMode() const { return view_state_.mode; }
  // The mode actually drawn: Photo without a controller, without a photo, or while a tool that
  // edits the photo is active; else viewMode().
  CanvasViewMode shownMode() const;
  // Whether the photo is visible at a widget point (Photo, Onion, left of the divider): where
  // sources may be edited.
  bool photoVisibleAt(const QPointF& widget) const;
  // The photo pixel under a widget point: the point itself where the photo shows; over the
  // result, the photo pixel the result shows there, through `inverse` (null: resultInverse()),
  // or none and a status line saying why and what to do.
  PhotoPoint photoPixelAt(const QPointF& widget, const ResultInverse* inverse = nullptr) const;
  // Where a photo pixel is drawn: at itself where the photo shows it, else where the result
  // shows it (the camera's forward map); empty where the result does not show it.
  std::optional<QPointF> widgetFromPhotoPixel(const Eigen::Vector2d& photo_px) const;
  // The inverse of the camera the result shows now (result_inverse.h), made on first use after
  // each camera or photo change; a gesture keeps the one it began with.
  std::shared_ptr<const ResultInverse> resultInverse() const;
  // The newest result delivered for the current photo; null before the first one.
  const QImage* resultImage() const;
  // The divider's widget x in Split.
  double dividerX() const;

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
  void setViewState(const CanvasViewState& state);
  void setViewMode(CanvasViewMode mode);
  void toggleBeforeAfter();  // `\`
  void setSplit(double fraction);
  void setOnionOpacity(double opacity);
  // Guides over the picture (grid_overlay.h).
  void setGridVisible(bool visible);
  // The residual vectors from fitted to clicked targets, ×10 (canvas_annotations.h).
  void setResidualsMagnified(bool magnified);
  // A tool's one-line message for the status bar (a refused gesture and why).
  void showToolMessage(const QString& message) { emit toolMessage(message); }

 signals:
  void viewChanged();
  void viewStateChanged();
  void toolChanged();  // setTool made another tool active
  void cursorMoved(const QPointF& image_point);
  void toolMessage(const QString& message);

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
  // canvas_result.cpp: the picture of the shown mode, and the Split/Onion controls.
  void paintPicture(QPainter& painter, const QRectF& image_rect);
  void paintResult(QPainter& painter, const QRectF& image_rect);
  void paintViewBadge(QPainter& painter, const QRectF& image_rect);
  // paintDepth only where the photo shows (depth is of photo pixels).
  void paintDepthOnPhoto(QPainter& painter, const QRectF& image_rect);
  bool onDividerHandle(const QPointF& widget) const;
  // The picture the loupe magnifies at a widget point (the result or the photo's display).
  const QImage& loupePicture(const QPointF& widget) const;
  void paintResidualAids(QPainter& painter);  // the legend and magnified residuals
  void userMovedView();
  void pinchBy(double factor, const QPointF& widget_centre);

  Document* document_;
  ViewTransform view_;
  ScaledImageCache display_cache_;  // the display copy at the current zoom
  std::unique_ptr<Tool> tool_;
  DepthOverlay* depth_overlay_ = nullptr;
  PreviewController* preview_ = nullptr;
  CanvasViewState view_state_;
  ScaledImageCache result_cache_;  // the result at the current zoom
  // Results with a generation above this are of the current photo: the controller schedules
  // the new photo's render on cameraChanged, which Document emits after photoChanged.
  quint64 photo_generation_floor_ = 0;
  const void* floor_photo_ = nullptr;  // the photo the floor was taken for
  bool dragging_divider_ = false;
  QMetaObject::Connection camera_connection_;  // the "updating" badge's repaint
  mutable std::shared_ptr<const ResultInverse> result_inverse_;  // reset on camera changes
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
