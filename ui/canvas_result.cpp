// SPDX-License-Identifier: Apache-2.0
// The canvas's photo/result picture (canvas_view_mode.h; the decisions are in canvas.h).
#include "ui/canvas.h"

#include "ui/document.h"
#include "ui/preview_controller.h"
#include "ui/tools/tool.h"

#include <QPainter>
#include <QPixmap>

#include <cmath>
#include <memory>
#include <utility>

namespace artcam::ui {
namespace {

constexpr double kDividerHandleRadius = 9.0;  // widget px

// A checkerboard under the result, so its transparent pixels (no preimage) read as such.
void paintChecker(QPainter& painter, const QRectF& r) {
  static const QPixmap tile = [] {
    constexpr int kCell = 8;
    QPixmap p(2 * kCell, 2 * kCell);
    p.fill(QColor(90, 90, 90));
    QPainter tp(&p);
    tp.fillRect(0, 0, kCell, kCell, QColor(120, 120, 120));
    tp.fillRect(kCell, kCell, kCell, kCell, QColor(120, 120, 120));
    return p;
  }();
  painter.fillRect(r, QBrush(tile));
}

}  // namespace

void Canvas::setPreview(PreviewController* preview) {
  if (preview_) disconnect(preview_, nullptr, this, nullptr);
  disconnect(camera_connection_);
  preview_ = preview;
  // Whatever the controller holds now is taken to be of the current document.
  photo_generation_floor_ = 0;
  floor_photo_ = document_->photo().get();
  if (preview_) {
    // A result, or a request that makes the badge say "updating": repaint only if it shows.
    const auto update_if_result_shown = [this] {
      if (shownMode() != CanvasViewMode::Photo) update();
    };
    connect(preview_, &PreviewController::previewChanged, this, update_if_result_shown);
    camera_connection_ = connect(document_, &Document::cameraChanged, this, update_if_result_shown);
  }
  update();
}

CanvasViewMode Canvas::shownMode() const {
  if (!preview_ || !document_->photo() || (tool_ && !tool_->worksOnResult()))
    return CanvasViewMode::Photo;
  return view_state_.mode;
}

bool Canvas::photoVisibleAt(const QPointF& widget) const {
  switch (shownMode()) {
    case CanvasViewMode::Photo:
    case CanvasViewMode::Onion:
      return true;
    case CanvasViewMode::Result:
      return false;
    case CanvasViewMode::Split:
      return widget.x() < dividerX();
  }
  return true;
}

std::shared_ptr<const ResultInverse> Canvas::resultInverse() const {
  if (!result_inverse_)
    result_inverse_ =
        std::make_shared<const ResultInverse>(document_->artcam(), document_->frame());
  return result_inverse_;
}

PhotoPoint Canvas::photoPixelAt(const QPointF& widget, const ResultInverse* inverse) const {
  const QPointF p = view_.imageFromWidget(widget);
  if (photoVisibleAt(widget)) return {Eigen::Vector2d(p.x(), p.y()), QString()};
  // The result is drawn in the photo's frame, so its pixel under the cursor is p too.
  if (inverse) return inverse->photoPixelOf({p.x(), p.y()});
  return resultInverse()->photoPixelOf({p.x(), p.y()});
}

std::optional<QPointF> Canvas::widgetFromPhotoPixel(const Eigen::Vector2d& photo_px) const {
  const QPointF direct = view_.widgetFromImage(QPointF(photo_px.x(), photo_px.y()));
  const CanvasViewMode shown = shownMode();
  if (shown == CanvasViewMode::Photo || shown == CanvasViewMode::Onion) return direct;
  if (shown == CanvasViewMode::Split && direct.x() < dividerX()) return direct;
  const std::optional<Eigen::Vector2d> r = resultInverse()->resultPixelOf(photo_px);
  if (!r) return std::nullopt;
  return view_.widgetFromImage(QPointF(r->x(), r->y()));
}

const QImage* Canvas::resultImage() const {
  if (!preview_ || preview_->image().isNull()) return nullptr;
  if (preview_->imageGeneration() <= photo_generation_floor_) return nullptr;  // older photo's
  return &preview_->image();
}

double Canvas::dividerX() const { return view_state_.split * width(); }

void Canvas::setViewState(const CanvasViewState& state) {
  CanvasViewState s = state;
  s.split = clampedFraction(s.split);
  s.onion_opacity = clampedFraction(s.onion_opacity);
  if (s == view_state_) return;
  view_state_ = s;
  update();
  emit viewStateChanged();
}

void Canvas::setViewMode(CanvasViewMode mode) { setViewState(withMode(view_state_, mode)); }

void Canvas::toggleBeforeAfter() { setViewState(toggledBeforeAfter(view_state_)); }

void Canvas::setSplit(double fraction) {
  CanvasViewState s = view_state_;
  s.split = fraction;
  setViewState(s);
}

void Canvas::setOnionOpacity(double opacity) {
  CanvasViewState s = view_state_;
  s.onion_opacity = opacity;
  setViewState(s);
}

bool Canvas::onDividerHandle(const QPointF& widget) const {
  if (shownMode() != CanvasViewMode::Split) return false;
  return std::hypot(widget.x() - dividerX(), widget.y() - height() / 2.0) <=
         kDividerHandleRadius + 2.0;
}

const QImage& Canvas::loupePicture(const QPointF& widget) const {
  const QImage* result = resultImage();
  if (result && !photoVisibleAt(widget)) return *result;
  return document_->photo()->display;
}

void Canvas::paintPicture(QPainter& painter, const QRectF& image_rect) {
  const QImage& photo = document_->photo()->display;
  switch (shownMode()) {
    case CanvasViewMode::Photo:
      display_cache_.draw(painter, image_rect, photo);
      break;
    case CanvasViewMode::Result:
      paintChecker(painter, image_rect.intersected(QRectF(rect())));
      paintResult(painter, image_rect);
      break;
    case CanvasViewMode::Onion:
      // Transparent result pixels show the photo, so no checkerboard here.
      display_cache_.draw(painter, image_rect, photo);
      painter.save();
      painter.setOpacity(view_state_.onion_opacity);
      paintResult(painter, image_rect);
      painter.restore();
      break;
    case CanvasViewMode::Split: {
      const double x = dividerX();
      painter.save();
      painter.setClipRect(QRectF(0, 0, x, height()));
      display_cache_.draw(painter, image_rect, photo);
      painter.setClipRect(QRectF(x, 0, width() - x, height()));
      paintChecker(painter, image_rect.intersected(QRectF(rect())));
      paintResult(painter, image_rect);
      painter.restore();
      break;
    }
  }
}

void Canvas::paintDepthOnPhoto(QPainter& painter, const QRectF& image_rect) {
  switch (shownMode()) {
    case CanvasViewMode::Result:
      return;
    case CanvasViewMode::Split:
      painter.save();
      painter.setClipRect(QRectF(0, 0, dividerX(), height()));
      paintDepth(painter, image_rect);
      painter.restore();
      return;
    case CanvasViewMode::Photo:
    case CanvasViewMode::Onion:
      paintDepth(painter, image_rect);
      return;
  }
}

void Canvas::paintResult(QPainter& painter, const QRectF& image_rect) {
  const QImage* result = resultImage();
  if (!result) return;
  // The preview may be smaller than the photo: its own scale decides smooth vs nearest, by the
  // photo's rule (smooth when minifying, nearest when magnifying so pixels show), except that a
  // coarse pass (¼ size, while a slow final renders) is always smoothed: its pixels mean nothing.
  const double result_scale = image_rect.width() / result->width();
  painter.save();
  painter.setRenderHint(QPainter::SmoothPixmapTransform,
                        result_scale < 1.0 || !preview_->imageIsFinal());
  result_cache_.draw(painter, image_rect, *result);
  painter.restore();
}

void Canvas::paintViewBadge(QPainter& painter, const QRectF& image_rect) {
  if (!preview_) return;
  const CanvasViewMode shown = shownMode();
  const bool shows_result = shown != CanvasViewMode::Photo;
  painter.save();
  if (shown == CanvasViewMode::Split) {
    const double x = dividerX();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(QPen(QColor(0, 0, 0, 160), 3.0));
    painter.drawLine(QPointF(x, 0), QPointF(x, height()));
    painter.setPen(QPen(Qt::white, 1.0));
    painter.drawLine(QPointF(x, 0), QPointF(x, height()));
    const QPointF c(x, height() / 2.0);
    painter.setBrush(QColor(40, 40, 44, 220));
    painter.setPen(QPen(Qt::white, 1.5));
    painter.drawEllipse(c, kDividerHandleRadius, kDividerHandleRadius);
    painter.drawText(QRectF(c.x() - kDividerHandleRadius, c.y() - kDividerHandleRadius,
                            2 * kDividerHandleRadius, 2 * kDividerHandleRadius),
                     Qt::AlignCenter, QStringLiteral("↔"));
  }
  QString text;
  switch (shown) {
    case CanvasViewMode::Photo:
      text = view_state_.mode != CanvasViewMode::Photo ? tr("Photo (this tool edits the photo)")
                                                       : tr("Photo");
      break;
    case CanvasViewMode::Result:
      text = tr("Result");
      break;
    case CanvasViewMode::Split:
      text = tr("Photo | Result");
      break;
    case CanvasViewMode::Onion:
      text = tr("Result over photo, %1 %").arg(std::lround(view_state_.onion_opacity * 100));
      break;
  }
  const bool has_result = resultImage() != nullptr;
  if (shows_result && !has_result) {
    // Nothing of this photo yet: say so over the checkerboard rather than show the photo.
    painter.setPen(QColor(230, 230, 230));
    painter.drawText(image_rect.intersected(QRectF(rect())), Qt::AlignCenter,
                     tr("Rendering the result…"));
  } else if (shows_result && (preview_->imageGeneration() < preview_->requestedGeneration() ||
                              !preview_->imageIsFinal())) {
    text += tr(" — updating");
  }
  const QFontMetrics fm = painter.fontMetrics();
  const QRectF badge(width() / 2.0 - (fm.horizontalAdvance(text) + 16) / 2.0, 8,
                     fm.horizontalAdvance(text) + 16, fm.height() + 6);
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(0, 0, 0, 150));
  painter.drawRoundedRect(badge, 4, 4);
  painter.setPen(Qt::white);
  painter.drawText(badge, Qt::AlignCenter, text);
  painter.restore();
}

}  // namespace artcam::ui
