// SPDX-License-Identifier: Apache-2.0
#include "ui/canvas.h"

#include "ui/canvas_annotations.h"
#include "ui/depth_overlay.h"
#include "ui/document.h"
#include "ui/grid_overlay.h"
#include "ui/line_annotations.h"
#include "ui/preview_controller.h"
#include "ui/tools/tool.h"

#include <QGestureEvent>
#include <QKeyEvent>
#include <QNativeGestureEvent>
#include <QPinchGesture>
#include <QLinearGradient>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

namespace artcam::ui {
namespace {

QPointF toQt(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

void drawArrow(QPainter& painter, const QPointF& from, const QPointF& to) {
  painter.drawLine(from, to);
  const QPointF d = to - from;
  const double len = std::hypot(d.x(), d.y());
  if (len < 6.0) return;
  const QPointF u = d / len;
  const QPointF n(-u.y(), u.x());
  constexpr double kHead = 8.0;
  QPainterPath head;
  head.moveTo(to);
  head.lineTo(to - u * kHead + n * kHead * 0.45);
  head.lineTo(to - u * kHead - n * kHead * 0.45);
  head.closeSubpath();
  painter.fillPath(head, painter.pen().color());
}

}  // namespace

Canvas::Canvas(Document* document, QWidget* parent) : QWidget(parent), document_(document) {
  setMouseTracking(true);  // tools draw rubber lines to the cursor
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(200, 150);
  setAttribute(Qt::WA_OpaquePaintEvent);
  grabGesture(Qt::PinchGesture);
  connect(document_, &Document::photoChanged, this, &Canvas::onPhotoChanged);
  // The full photo's picture replaces the first look's: same frame, so the view stays.
  connect(document_, &Document::photoRefined, this, qOverload<>(&QWidget::update));
  connect(document_, &Document::pairsChanged, this, qOverload<>(&QWidget::update));
  connect(document_, &Document::linesChanged, this, qOverload<>(&QWidget::update));
  connect(document_->depth(), &DepthModel::depthChanged, this, qOverload<>(&QWidget::update));
  connect(document_->depth(), &DepthModel::activeLayerChanged, this,
          qOverload<>(&QWidget::update));
  connect(document_, &Document::selectionChanged, this, qOverload<>(&QWidget::update));
  // The result's inverse is of one camera; a gesture that needs the old one holds it.
  connect(document_, &Document::cameraChanged, this, [this] { result_inverse_.reset(); });
}

Canvas::~Canvas() = default;

void Canvas::setTool(std::unique_ptr<Tool> tool) {
  if (tool_) tool_->cancel();
  tool_ = std::move(tool);
  applyCursor();
  update();
  emit toolChanged();
}

void Canvas::applyCursor() {
  if (panning_)
    setCursor(Qt::ClosedHandCursor);
  else if (space_down_)
    setCursor(Qt::OpenHandCursor);
  else
    setCursor(tool_ ? tool_->cursor() : QCursor(Qt::ArrowCursor));
}

void Canvas::setSpacePan(bool down) {
  if (space_down_ == down) return;
  space_down_ = down;
  applyCursor();
}

void Canvas::setDepthOverlay(DepthOverlay* overlay) {
  depth_overlay_ = overlay;
  if (overlay) connect(overlay, &DepthOverlay::changed, this, qOverload<>(&QWidget::update));
  update();
}

QColor Canvas::residualColour(double residual_px) {
  if (residual_px < 0.0 || !std::isfinite(residual_px)) return QColor(255, 40, 40);
  const double t = std::clamp(residual_px / kRedResidualPx, 0.0, 1.0);
  // Through yellow so mid residuals read as "warning", not as a muddy brown.
  const int r = static_cast<int>(std::lround(255 * std::min(1.0, 2 * t)));
  const int g = static_cast<int>(std::lround(220 * std::min(1.0, 2 * (1 - t))));
  return QColor(r, g, 40);
}

void Canvas::zoomToFit() {
  if (!document_->photo()) return;
  const FrameSize f = document_->frame();
  view_.fit(QSizeF(size()), QSizeF(f.width, f.height));
  follow_fit_ = true;
  update();
  emit viewChanged();
}

void Canvas::zoomActual() {
  view_.setScaleAt(1.0, QPointF(width() / 2.0, height() / 2.0));
  userMovedView();
}

void Canvas::zoomIn() {
  view_.zoomAt(1.25, QPointF(width() / 2.0, height() / 2.0));
  userMovedView();
}

void Canvas::zoomOut() {
  view_.zoomAt(1.0 / 1.25, QPointF(width() / 2.0, height() / 2.0));
  userMovedView();
}

void Canvas::setView(double scale, const QPointF& image_centre) {
  view_.setScaleAt(scale, QPointF(width() / 2.0, height() / 2.0));
  view_.setCentre(QSizeF(size()), image_centre);
  userMovedView();
}

void Canvas::setLoupeEnabled(bool enabled) {
  loupe_enabled_ = enabled;
  update();
}

LoupeGeometry Canvas::loupe() const {
  if (!loupe_enabled_ || !cursor_inside_ || !tool_ || !tool_->wantsLoupe() || !document_->photo())
    return {};
  return Loupe::geometry(size(), cursor_widget_, view_.imageFromWidget(cursor_widget_),
                         view_.scale());
}

void Canvas::pinchBy(double factor, const QPointF& widget_centre) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  view_.zoomAt(factor, widget_centre);
  userMovedView();
}

bool Canvas::event(QEvent* event) {
  if (event->type() == QEvent::NativeGesture) {
    // Touchpad pinch (macOS, libinput on Wayland/X11): value() is the scale change this step.
    auto* g = static_cast<QNativeGestureEvent*>(event);
    if (g->gestureType() == Qt::ZoomNativeGesture) {
      pinchBy(1.0 + g->value(), g->position());
      return true;
    }
  } else if (event->type() == QEvent::Gesture) {
    // Touch-screen pinch: scaleFactor() is the change since the last event.
    auto* ge = static_cast<QGestureEvent*>(event);
    if (auto* pinch = static_cast<QPinchGesture*>(ge->gesture(Qt::PinchGesture))) {
      if (pinch->changeFlags() & QPinchGesture::ScaleFactorChanged)
        pinchBy(pinch->scaleFactor(), mapFromGlobal(pinch->centerPoint()));
      ge->accept(pinch);
      return true;
    }
  }
  return QWidget::event(event);
}

void Canvas::userMovedView() {
  follow_fit_ = false;
  update();
  emit viewChanged();
}

void Canvas::onPhotoChanged() {
  if (tool_) tool_->cancel();
  result_inverse_.reset();
  if (preview_ && document_->photo().get() != floor_photo_)
    photo_generation_floor_ = preview_->requestedGeneration();
  floor_photo_ = document_->photo().get();
  zoomToFit();
}

void Canvas::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(48, 48, 52));
  const PhotoPtr& photo = document_->photo();
  if (!photo) {
    painter.setPen(QColor(180, 180, 180));
    painter.drawText(rect(), Qt::AlignCenter, tr("Open a photo (Ctrl+O) or drop one here"));
    return;
  }
  const FrameSize f = photo->size();
  const QRectF target = view_.widgetFromImage(QRectF(0, 0, f.width, f.height));
  // Smooth when minifying; nearest when magnifying so pixels are visible for precise clicks.
  painter.setRenderHint(QPainter::SmoothPixmapTransform, view_.scale() < 1.0);
  paintPicture(painter, target);
  paintDepthOnPhoto(painter, target);
  if (grid_visible_) paintGridOverlay(painter, target);
  painter.setRenderHint(QPainter::Antialiasing, true);
  paintLines(painter, *this, *document_);
  paintPairs(painter);
  paintResidualAids(painter);
  if (tool_) tool_->paint(painter);
  paintViewBadge(painter, target);
  if (const LoupeGeometry g = loupe(); g.isValid())
    Loupe::paint(painter, g, loupePicture(cursor_widget_), QSize(f.width, f.height));
}

void Canvas::paintDepth(QPainter& painter, const QRectF& image_rect) {
  if (!depth_overlay_ || !depth_overlay_->isVisible() || depth_overlay_->image().isNull()) return;
  painter.save();
  painter.setOpacity(depth_overlay_->opacity());
  painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
  painter.drawImage(image_rect, depth_overlay_->image());
  painter.restore();
  // Legend: the ramp from far (left) to near (right) with the depth range.
  const QRectF bar(12, height() - 34, 180, 12);
  QLinearGradient g(bar.topLeft(), bar.topRight());
  for (int k = 0; k <= 8; ++k) g.setColorAt(k / 8.0, DepthOverlay::ramp(k / 8.0));
  painter.fillRect(bar.adjusted(-6, -18, 6, 6), QColor(0, 0, 0, 150));
  painter.fillRect(bar, g);
  painter.setPen(Qt::white);
  const double zmin = depth_overlay_->minDepth(), zmax = depth_overlay_->maxDepth();
  painter.drawText(QRectF(bar.left(), bar.top() - 16, bar.width(), 14), Qt::AlignLeft,
                   tr("far %1").arg(zmax, 0, 'g', 4));
  painter.drawText(QRectF(bar.left(), bar.top() - 16, bar.width(), 14), Qt::AlignRight,
                   tr("near %1").arg(zmin, 0, 'g', 4));
}

void Canvas::paintPairs(QPainter& painter) {
  const auto& pairs = document_->pairs();
  // A hand-set camera was not fitted to the pairs: their residuals would colour good pairs
  // red, so they are drawn neutral while the banner (manual_camera_banner.h) says why.
  const bool manual = document_->manualCamera().has_value();
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const int index = static_cast<int>(i);
    const QPointF s = view_.widgetFromImage(toQt(p.source));
    const QPointF t = view_.widgetFromImage(toQt(p.target));
    const bool selected = document_->isSelected(index);
    const QColor colour = !p.enabled ? QColor(150, 150, 150)
                          : manual   ? kUnfittedPairColour
                                     : residualColour(document_->residual(index));
    if (selected) {
      painter.setPen(QPen(QColor(80, 160, 255), 5.0));
      painter.drawLine(s, t);
    }
    painter.setPen(QPen(colour, 2.0, p.enabled ? Qt::SolidLine : Qt::DashLine));
    drawArrow(painter, s, t);
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(Qt::black, 3.0));
    painter.drawEllipse(s, 4.5, 4.5);
    painter.setPen(QPen(selected ? QColor(80, 160, 255) : Qt::white, 1.5));
    painter.drawEllipse(s, 4.5, 4.5);
    painter.setBrush(colour);
    painter.setPen(QPen(Qt::black, 1.0));
    painter.drawRect(QRectF(t.x() - 3.5, t.y() - 3.5, 7, 7));
    painter.setBrush(Qt::NoBrush);
    drawHaloText(painter, s + QPointF(6, -6), QString::number(index + 1), Qt::white,
                 QColor(0, 0, 0, 220));
  }
}

void Canvas::paintResidualAids(QPainter& painter) {
  // Only while the pairs are fitted: a hand-set camera draws them neutral (no ramp to explain).
  if (document_->pairs().empty() || document_->manualCamera()) return;
  if (residuals_magnified_) paintMagnifiedResiduals(painter, view_, *document_);
  paintResidualLegend(painter, size());
}

void Canvas::setGridVisible(bool visible) {
  grid_visible_ = visible;
  update();
}

void Canvas::setResidualsMagnified(bool magnified) {
  residuals_magnified_ = magnified;
  update();
}

void Canvas::resizeEvent(QResizeEvent*) {
  if (follow_fit_) zoomToFit();
}

void Canvas::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::MiddleButton || (event->button() == Qt::LeftButton && space_down_)) {
    panning_ = true;
    pan_last_ = event->position().toPoint();
    setCursor(Qt::ClosedHandCursor);
    return;
  }
  // The wipe's divider: its handle, or Alt+drag anywhere, before the tool sees the press.
  if (event->button() == Qt::LeftButton && shownMode() == CanvasViewMode::Split &&
      (onDividerHandle(event->position()) || event->modifiers().testFlag(Qt::AltModifier))) {
    dragging_divider_ = true;
    setSplit(event->position().x() / std::max(1, width()));
    return;
  }
  cursor_widget_ = event->position();
  cursor_inside_ = true;
  if (tool_ && document_->photo()) tool_->mousePress(event);
  if (tool_ && tool_->wantsLoupe()) update();
}

void Canvas::mouseMoveEvent(QMouseEvent* event) {
  if (panning_) {
    const QPoint p = event->position().toPoint();
    view_.panBy(QPointF(p - pan_last_));
    pan_last_ = p;
    userMovedView();
    return;
  }
  if (dragging_divider_) {
    setSplit(event->position().x() / std::max(1, width()));
    return;
  }
  cursor_widget_ = event->position();
  cursor_inside_ = true;
  emit cursorMoved(view_.imageFromWidget(event->position()));
  if (tool_ && document_->photo()) tool_->mouseMove(event);
  if (event->buttons() == Qt::NoButton && onDividerHandle(event->position()))
    setCursor(Qt::SplitHCursor);
  if (tool_ && tool_->wantsLoupe()) update();  // the loupe follows the cursor
}

void Canvas::mouseReleaseEvent(QMouseEvent* event) {
  if (panning_) {
    if (event->button() == Qt::MiddleButton || event->button() == Qt::LeftButton) {
      panning_ = false;
      applyCursor();
    }
    return;
  }
  if (dragging_divider_) {
    if (event->button() == Qt::LeftButton) dragging_divider_ = false;
    return;
  }
  if (tool_ && document_->photo()) tool_->mouseRelease(event);
}

void Canvas::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps == 0.0) return;
  view_.zoomAt(std::pow(1.25, steps), event->position());
  userMovedView();
}

void Canvas::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Space) {
    if (!event->isAutoRepeat()) setSpacePan(true);
    return;
  }
  if (tool_ && tool_->keyPress(event)) return;
  QWidget::keyPressEvent(event);
}

void Canvas::keyReleaseEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Space) {
    if (!event->isAutoRepeat()) setSpacePan(false);
    return;
  }
  QWidget::keyReleaseEvent(event);
}

void Canvas::leaveEvent(QEvent* event) {
  cursor_inside_ = false;
  update();
  QWidget::leaveEvent(event);
}

}  // namespace artcam::ui
