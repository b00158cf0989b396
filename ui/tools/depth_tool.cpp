// SPDX-License-Identifier: Apache-2.0
#include "ui/tools/depth_tool.h"

#include "ui/canvas.h"
#include "ui/depth_mask_tint.h"
#include "ui/tools/tool_cursor.h"
#include "ui/depth_commands.h"
#include "ui/document.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace artcam::ui {
namespace {

QString tr(const char* text) { return QCoreApplication::translate("DepthTool", text); }
// The active mask's tint: cyan, away from the overlay's red→blue depth ramp; reduced to at
// most this many pixels on its long side (a tint needs no more), so it costs < 1 ms a repaint.
const QColor kMaskTint(40, 220, 255);
constexpr int kMaskTintMaxSide = 512;

}  // namespace

DepthTool::DepthTool(Canvas* canvas, Document* document, DepthToolSettings* settings,
                     DepthToolMode mode)
    : Tool(canvas, document), settings_(settings), mode_(mode) {}

DepthModel* DepthTool::depth() const { return document_->depth(); }

std::optional<Eigen::Vector2d> DepthTool::photoPoint(const QPointF& widget, bool say_why) const {
  const PhotoPoint p = canvas_->photoPixelAt(widget, stroke_inverse_.get());
  if (!p.pixel && say_why) canvas_->showToolMessage(p.refusal);
  return p.pixel;
}

QPointF DepthTool::widgetPoint(const Eigen::Vector2d& photo_px) const {
  // Off screen (never hit, never seen) where the result shows no such photo pixel.
  return canvas_->widgetFromPhotoPixel(photo_px).value_or(QPointF(-1e9, -1e9));
}

int DepthTool::ensureLayer() {
  if (depth()->activeLayer() >= 0) return depth()->activeLayer();
  document_->undoStack()->push(new AddDepthLayerCommand(depth(), depth()->makeLayer()));
  return depth()->activeLayer();
}

BrushOptions DepthTool::brush() const {
  return {settings_->radius(), settings_->hardness(), mode_ == DepthToolMode::Eraser};
}

void DepthTool::mousePress(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  cursor_widget_ = event->position();
  // A stroke maps its whole path through the camera it began under (its own dabs may change
  // the depth the effects read, never where pixels go, but a refit could).
  if (mode_ == DepthToolMode::Brush || mode_ == DepthToolMode::Eraser)
    stroke_inverse_ = canvas_->resultInverse();
  // A press on a drawn handle (a depth point, the polygon's first vertex) needs no photo pixel.
  const bool closes =
      mode_ == DepthToolMode::Polygon && polygon_.size() >= 3 &&
      QLineF(widgetPoint(polygon_.front()), event->position()).length() <= kHitRadius;
  const bool on_handle = closes || (mode_ == DepthToolMode::Points && hitAnchor(event->position()));
  const std::optional<Eigen::Vector2d> at = photoPoint(event->position(), !on_handle);
  if (!at && !on_handle) {
    stroke_inverse_.reset();
    canvas_->update();
    return;
  }
  const Eigen::Vector2d p = at.value_or(Eigen::Vector2d::Zero());
  switch (mode_) {
    case DepthToolMode::Brush:
    case DepthToolMode::Eraser: {
      // The new layer and the first stroke are one undo step.
      stroke_made_layer_ = depth()->activeLayer() < 0;
      if (stroke_made_layer_) document_->undoStack()->beginMacro(tr("Paint depth region"));
      stroke_layer_ = ensureLayer();
      RegionMask* mask = depth()->maskForStroke(stroke_layer_);
      stroke_before_ = *mask;
      stroke_edges_.reset();
      // Edge-aware strokes read full-resolution pixels: during a first look (no full image
      // yet, under a second after opening) the brush paints plain; it never reads reduced ones.
      if (settings_->edgeAware() && document_->photo() && document_->photo()->hasFullImage()) {
        const ImageF& photo = document_->photo()->full.image;
        const int px = static_cast<int>(std::floor(p.x())), py = static_cast<int>(std::floor(p.y()));
        if (px >= 0 && py >= 0 && px < photo.width && py < photo.height)
          stroke_edges_ = EdgeAwareOptions{photoColourAt(photo, px, py), settings_->edgeTolerance()};
      }
      stroke_rect_ = strokeDab(mask, p, p, /*first=*/true);
      stroke_last_ = p;
      stroke_gap_ = false;
      depth()->maskEdited(stroke_layer_, stroke_rect_);
      break;
    }
    case DepthToolMode::Polygon:
      if (closes) {
        closePolygon(event->modifiers().testFlag(Qt::AltModifier));
      } else {
        polygon_.push_back(p);
      }
      break;
    case DepthToolMode::Points:
      pressPoints(event->position());
      break;
  }
  canvas_->update();
}

void DepthTool::pressPoints(const QPointF& widget) {
  const int layer = ensureLayer();
  if (const auto hit = hitAnchor(widget)) {
    drag_anchor_ = *hit;
    drag_before_ = depth()->layer(layer).anchors;
    return;
  }
  const std::optional<Eigen::Vector2d> at = photoPoint(widget, false);
  if (!at) return;  // mousePress said why
  const Eigen::Vector2d p = *at;
  std::vector<DepthAnchor> anchors = depth()->layer(layer).anchors;
  if (static_cast<int>(anchors.size()) < DepthModel::kAnchorCount) {
    anchors.push_back({p, settings_->nextDepth()});
  } else {
    size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < anchors.size(); ++i)
      if (const double d = (anchors[i].pixel - p).norm(); d < best) {
        best = d;
        nearest = i;
      }
    anchors[nearest] = {p, settings_->nextDepth()};
  }
  document_->undoStack()->push(
      new SetDepthAnchorsCommand(depth(), layer, std::move(anchors), tr("Place depth point")));
}

std::optional<int> DepthTool::hitAnchor(const QPointF& widget) const {
  const int layer = depth()->activeLayer();
  if (layer < 0) return std::nullopt;
  const auto& anchors = depth()->layer(layer).anchors;
  std::optional<int> best;
  double best_d = kHitRadius;
  for (size_t i = 0; i < anchors.size(); ++i) {
    const double d = QLineF(widgetPoint(anchors[i].pixel), widget).length();
    if (d <= best_d) {
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void DepthTool::mouseMove(QMouseEvent* event) {
  cursor_widget_ = event->position();
  cursor_inside_ = true;
  const bool dragging =
      event->buttons().testFlag(Qt::LeftButton) && (stroke_layer_ >= 0 || drag_anchor_ >= 0);
  const std::optional<Eigen::Vector2d> at =
      dragging ? photoPoint(event->position(), false) : std::nullopt;
  if (dragging && !at) {
    // No photo pixel under the cursor: this dab is skipped, and the stroke resumes with a
    // fresh dab rather than a segment across what the result does not show.
    stroke_gap_ = true;
  } else if (stroke_layer_ >= 0 && dragging) {
    const Eigen::Vector2d p = *at;
    RegionMask* mask = depth()->maskForStroke(stroke_layer_);
    const PixelRect r = strokeDab(mask, stroke_gap_ ? p : stroke_last_, p, /*first=*/false);
    stroke_last_ = p;
    stroke_gap_ = false;
    stroke_rect_ = stroke_rect_.united(r);
    depth()->maskEdited(stroke_layer_, r);
  } else if (drag_anchor_ >= 0 && dragging) {
    const Eigen::Vector2d p = *at;
    // Live while dragging; the undo step is pushed on release with the press-time values.
    std::vector<DepthAnchor> anchors = depth()->layer(depth()->activeLayer()).anchors;
    if (drag_anchor_ < static_cast<int>(anchors.size())) {
      anchors[static_cast<size_t>(drag_anchor_)].pixel = p;
      depth()->setAnchors(depth()->activeLayer(), std::move(anchors));
    }
  }
  canvas_->update();
}

void DepthTool::mouseRelease(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  if (stroke_layer_ >= 0) finishStroke();
  if (drag_anchor_ >= 0) {
    const int layer = depth()->activeLayer();
    std::vector<DepthAnchor> after = depth()->layer(layer).anchors;
    if (after != drag_before_) {
      depth()->setAnchors(layer, drag_before_);  // the command's redo applies `after`
      document_->undoStack()->push(
          new SetDepthAnchorsCommand(depth(), layer, std::move(after), tr("Move depth point")));
    }
    drag_anchor_ = -1;
  }
  canvas_->update();
}

PixelRect DepthTool::strokeDab(RegionMask* mask, const Eigen::Vector2d& from,
                               const Eigen::Vector2d& to, bool first) {
  const ImageF* photo = document_->photo() ? &document_->photo()->full.image : nullptr;
  if (stroke_edges_ && photo && photo->width == mask->width() && photo->height == mask->height())
    return first ? stampEdgeAware(*mask, *photo, to, brush(), *stroke_edges_)
                 : segmentEdgeAware(*mask, *photo, from, to, brush(), *stroke_edges_);
  return first ? mask->stamp(to, brush()) : mask->segment(from, to, brush());
}

void DepthTool::finishStroke() {
  const int layer = stroke_layer_;
  stroke_layer_ = -1;
  const RegionMask* mask = depth()->maskForStroke(layer);
  // The layer must still be the one the stroke began on (same frame): a new photo mid-stroke
  // leaves nothing to record.
  if (mask && !stroke_rect_.empty() && mask->width() == stroke_before_.width() &&
      mask->height() == stroke_before_.height()) {
    document_->undoStack()->push(new PaintDepthMaskCommand(
        depth(), layer, stroke_rect_, stroke_before_.copyRect(stroke_rect_),
        mask->copyRect(stroke_rect_),
        mode_ == DepthToolMode::Eraser ? tr("Erase depth region") : tr("Paint depth region")));
  }
  if (stroke_made_layer_) document_->undoStack()->endMacro();
  stroke_made_layer_ = false;
  stroke_before_ = RegionMask();
  stroke_rect_ = {};
  stroke_edges_.reset();
  stroke_inverse_.reset();
}

void DepthTool::closePolygon(bool erase) {
  std::vector<Eigen::Vector2d> vertices = std::move(polygon_);
  polygon_.clear();
  if (vertices.size() < 3) return;
  QUndoStack* stack = document_->undoStack();
  stack->beginMacro(erase ? tr("Erase depth polygon") : tr("Fill depth polygon"));
  const int layer = ensureLayer();
  RegionMask* mask = depth()->maskForStroke(layer);
  RegionMask after = *mask;
  const PixelRect rect = after.fillPolygon(vertices, erase);
  if (!rect.empty())
    stack->push(new PaintDepthMaskCommand(depth(), layer, rect, mask->copyRect(rect),
                                          after.copyRect(rect),
                                          erase ? tr("Erase depth polygon")
                                                : tr("Fill depth polygon")));
  stack->endMacro();
}

bool DepthTool::keyPress(QKeyEvent* event) {
  if (mode_ != DepthToolMode::Polygon || polygon_.empty()) return false;
  switch (event->key()) {
    case Qt::Key_Return:
    case Qt::Key_Enter:
      closePolygon(event->modifiers().testFlag(Qt::AltModifier));
      break;
    case Qt::Key_Backspace:
      polygon_.pop_back();
      break;
    case Qt::Key_Escape:
      polygon_.clear();
      break;
    default:
      return false;
  }
  canvas_->update();
  return true;
}

void DepthTool::paintActiveMask(QPainter& painter) const {
  const int layer = depth()->activeLayer();
  if (layer < 0 || !document_->photo()) return;
  const RegionMask& mask = depth()->layer(layer).mask;
  if (mask.empty()) return;
  // A tint of the active plane's mask, so a stroke shows at once, before the plane has the
  // three depths the depth overlay needs: over the photo as it is, over the result warped as
  // the result warps the photo.
  const CanvasViewMode shown = canvas_->shownMode();
  const QRectF rect = canvas_->view().widgetFromImage(QRectF(0, 0, mask.width(), mask.height()));
  painter.save();
  painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
  if (shown != CanvasViewMode::Result) {
    if (shown == CanvasViewMode::Split)
      painter.setClipRect(QRectF(0, 0, canvas_->dividerX(), canvas_->height()));
    const int side = static_cast<int>(std::ceil(std::max(rect.width(), rect.height())));
    painter.drawImage(rect, maskTint(mask, kMaskTint, std::clamp(side, 1, kMaskTintMaxSide)));
  }
  painter.restore();
  if (shown == CanvasViewMode::Result || shown == CanvasViewMode::Split)
    paintMaskOnResult(painter, mask);
}

void DepthTool::paintMaskOnResult(QPainter& painter, const RegionMask& mask) const {
  const QRectF rect = canvas_->view().widgetFromImage(QRectF(0, 0, mask.width(), mask.height()));
  const int side = std::clamp(static_cast<int>(std::ceil(std::max(rect.width(), rect.height()))), 1,
                              kMaskTintMaxSide);
  const FrameSize grid = maskTintSize(mask, side);
  // The grid's photo pixels come from the warp's inverse map once per camera and size
  // (result_inverse.h); each repaint only looks the mask up.
  const QImage tint =
      maskTintThrough(mask, kMaskTint, grid, canvas_->resultInverse()->photoPixelsOfGrid(grid));
  painter.save();
  if (canvas_->shownMode() == CanvasViewMode::Split)
    painter.setClipRect(
        QRectF(canvas_->dividerX(), 0, canvas_->width() - canvas_->dividerX(), canvas_->height()));
  painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
  painter.drawImage(rect, tint);
  painter.restore();
}

void DepthTool::paint(QPainter& painter) {
  const ViewTransform& view = canvas_->view();
  paintActiveMask(painter);
  // Depth points of the active layer: numbered diamonds.
  if (const int layer = depth()->activeLayer(); layer >= 0) {
    const auto& anchors = depth()->layer(layer).anchors;
    for (size_t i = 0; i < anchors.size(); ++i) {
      const QPointF c = widgetPoint(anchors[i].pixel);
      QPainterPath diamond;
      diamond.moveTo(c + QPointF(0, -7));
      diamond.lineTo(c + QPointF(7, 0));
      diamond.lineTo(c + QPointF(0, 7));
      diamond.lineTo(c + QPointF(-7, 0));
      diamond.closeSubpath();
      painter.setPen(QPen(Qt::black, 1.5));
      painter.setBrush(QColor(255, 255, 255, 220));
      painter.drawPath(diamond);
      painter.setPen(Qt::white);
      painter.drawText(c + QPointF(9, -9),
                       QStringLiteral("%1: %2").arg(i + 1).arg(anchors[i].depth, 0, 'g', 4));
    }
  }
  painter.setBrush(Qt::NoBrush);
  if (mode_ == DepthToolMode::Polygon && !polygon_.empty()) {
    QPolygonF poly;
    for (const Eigen::Vector2d& v : polygon_) poly << widgetPoint(v);
    poly << cursor_widget_;
    painter.setPen(QPen(QColor(255, 200, 60), 1.5, Qt::DashLine));
    painter.drawPolyline(poly);
    painter.setPen(QPen(QColor(255, 200, 60), 1.5));
    painter.drawEllipse(poly.front(), kHitRadius * 0.6, kHitRadius * 0.6);
  }
  if ((mode_ == DepthToolMode::Brush || mode_ == DepthToolMode::Eraser) && cursor_inside_) {
    // The brush outline at its true size, and its hard core: a circle of photo pixels, so over
    // the result its image through the camera (what a dab there paints).
    const QPen outer =
        QPen(mode_ == DepthToolMode::Eraser ? QColor(255, 120, 120) : Qt::white, 1.0);
    const double hardness = settings_->hardness();
    if (const std::optional<QPolygonF> ring = resultRing(settings_->radius())) {
      painter.setPen(QPen(Qt::black, 2.0));
      painter.drawPolygon(*ring);
      painter.setPen(outer);
      painter.drawPolygon(*ring);
      if (settings_->radius() * hardness * view.scale() > 2.0)
        if (const auto core = resultRing(settings_->radius() * hardness)) {
          painter.setPen(QPen(Qt::white, 1.0, Qt::DotLine));
          painter.drawPolygon(*core);
        }
      return;
    }
    const double r = settings_->radius() * view.scale();
    painter.setPen(QPen(Qt::black, 2.0));
    painter.drawEllipse(cursor_widget_, r, r);
    painter.setPen(outer);
    painter.drawEllipse(cursor_widget_, r, r);
    const double core = r * hardness;
    if (core > 2.0) {
      painter.setPen(QPen(Qt::white, 1.0, Qt::DotLine));
      painter.drawEllipse(cursor_widget_, core, core);
    }
  }
}

std::optional<QPolygonF> DepthTool::resultRing(double radius_px) const {
  if (canvas_->photoVisibleAt(cursor_widget_)) return std::nullopt;
  const auto inverse = canvas_->resultInverse();
  const std::optional<Eigen::Vector2d> centre =
      canvas_->photoPixelAt(cursor_widget_, inverse.get()).pixel;
  if (!centre) return std::nullopt;
  constexpr int kSides = 48;
  QPolygonF ring;
  for (int k = 0; k < kSides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kSides;
    const auto r =
        inverse->resultPixelOf(*centre + radius_px * Eigen::Vector2d(std::cos(a), std::sin(a)));
    if (!r) return std::nullopt;  // across a pole: the plain circle says enough
    ring << canvas_->view().widgetFromImage(QPointF(r->x(), r->y()));
  }
  return ring;
}

void DepthTool::cancel() {
  if (stroke_layer_ >= 0) finishStroke();  // keep what was painted, as one step
  polygon_.clear();
  if (drag_anchor_ >= 0) {
    depth()->setAnchors(depth()->activeLayer(), drag_before_);
    drag_anchor_ = -1;
  }
}

QString DepthTool::name() const {
  switch (mode_) {
    case DepthToolMode::Brush: return tr("Depth brush");
    case DepthToolMode::Eraser: return tr("Depth eraser");
    case DepthToolMode::Polygon: return tr("Depth polygon");
    case DepthToolMode::Points: return tr("Depth points");
  }
  return {};
}

QCursor DepthTool::cursor() const {
  switch (mode_) {
    case DepthToolMode::Brush: return toolCursor(QStringLiteral("B"));
    case DepthToolMode::Eraser: return toolCursor(QStringLiteral("E"));
    case DepthToolMode::Polygon: return toolCursor(QStringLiteral("G"));
    case DepthToolMode::Points: return toolCursor(QStringLiteral("D"));
  }
  return {};
}

}  // namespace artcam::ui
