// SPDX-License-Identifier: Apache-2.0
#include "ui/line_annotations.h"

#include "core/render/attributed.h"
#include "ui/canvas.h"
#include "ui/canvas_annotations.h"
#include "ui/document.h"

#include <QCoreApplication>
#include <QPainter>
#include <QPolygonF>

namespace artcam::ui {
namespace {

const QColor kOpenLineColour{255, 220, 0};
const QColor kDisabledColour{150, 150, 150};

QString label(const LineTrace& line, const std::optional<LineBow>& bow) {
  const QString name = QString::fromStdString(line.label);
  if (!bow) return QCoreApplication::translate("Canvas", "L%1").arg(name);
  return QCoreApplication::translate("Canvas", "L%1  %2 px").arg(name).arg(bow->max_px, 0, 'f', 2);
}

void drawPolyline(QPainter& painter, const QPolygonF& points, const QColor& colour, bool dashed) {
  painter.setPen(QPen(QColor(0, 0, 0, 160), 4.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  painter.drawPolyline(points);
  painter.setPen(QPen(colour, 2.0, dashed ? Qt::DashLine : Qt::SolidLine, Qt::RoundCap,
                      Qt::RoundJoin));
  painter.drawPolyline(points);
  painter.setBrush(colour);
  painter.setPen(QPen(Qt::black, 1.0));
  for (const QPointF& p : points) painter.drawEllipse(p, 3.0, 3.0);
  painter.setBrush(Qt::NoBrush);
}

// The lines in widget coordinates: as traced (photo) or mapped through `geometry` (result).
void drawLines(QPainter& painter, const Canvas& canvas, const Document& document,
               const Camera* geometry) {
  const ViewTransform& view = canvas.view();
  auto widget = [&](const Eigen::Vector2d& p) -> std::optional<QPointF> {
    if (!geometry) return view.widgetFromImage(QPointF(p.x(), p.y()));
    const auto mapped = targetPixelFromSourcePixel(*geometry, p);
    if (!mapped) return std::nullopt;  // on the pole: that point is left out
    return view.widgetFromImage(QPointF(mapped->x(), mapped->y()));
  };
  const bool manual = document.manualCamera().has_value();
  for (size_t i = 0; i < document.lines().size(); ++i) {
    const LineTrace& line = document.lines()[i];
    QPolygonF points;
    for (const Eigen::Vector2d& p : line.points)
      if (const auto w = widget(p)) points << *w;
    if (points.isEmpty()) continue;
    const std::optional<LineBow> bow =
        manual ? std::nullopt : document.lineBow(static_cast<int>(i));
    const QColor colour = !line.enabled ? kDisabledColour
                          : bow         ? Canvas::residualColour(bow->max_px)
                                        : Canvas::kUnfittedPairColour;
    drawPolyline(painter, points, colour, !line.enabled);
    drawHaloText(painter, points.front() + QPointF(6, -8), label(line, bow), Qt::white,
                 QColor(0, 0, 0, 220));
  }
  QPolygonF open;
  for (const Eigen::Vector2d& p : document.openLine())
    if (const auto w = widget(p)) open << *w;
  if (!open.isEmpty()) drawPolyline(painter, open, kOpenLineColour, true);
}

}  // namespace

void paintLines(QPainter& painter, const Canvas& canvas, const Document& document) {
  if (document.lines().empty() && document.openLine().empty()) return;
  const Camera geometry = positionPart(document.camera());
  const double x = canvas.dividerX();
  const double w = canvas.width(), h = canvas.height();
  painter.save();
  switch (canvas.shownMode()) {
    case CanvasViewMode::Photo:
    case CanvasViewMode::Onion:
      drawLines(painter, canvas, document, nullptr);
      break;
    case CanvasViewMode::Result:
      drawLines(painter, canvas, document, &geometry);
      break;
    case CanvasViewMode::Split:
      painter.setClipRect(QRectF(0, 0, x, h));
      drawLines(painter, canvas, document, nullptr);
      painter.setClipRect(QRectF(x, 0, w - x, h));
      drawLines(painter, canvas, document, &geometry);
      break;
  }
  painter.restore();
}

}  // namespace artcam::ui
