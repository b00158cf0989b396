// SPDX-License-Identifier: Apache-2.0
#include "ui/canvas_annotations.h"

#include "core/render/attributed.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/view_transform.h"

#include <QCoreApplication>
#include <QLinearGradient>
#include <QPainter>
#include <QPainterPath>

#include <cmath>

namespace artcam::ui {

namespace {

QString tr(const char* text) { return QCoreApplication::translate("Canvas", text); }

}  // namespace

QRectF residualLegendBar(const QSize& size) {
  return {size.width() - 12.0 - 160.0, size.height() - 34.0, 160.0, 12.0};
}

void paintResidualLegend(QPainter& painter, const QSize& size) {
  const QRectF bar = residualLegendBar(size);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, false);
  painter.fillRect(bar.adjusted(-6, -18, 6, 6), QColor(0, 0, 0, 150));
  QLinearGradient g(bar.topLeft(), bar.topRight());
  for (int k = 0; k <= 8; ++k)
    g.setColorAt(k / 8.0, Canvas::residualColour(Canvas::kRedResidualPx * k / 8.0));
  painter.fillRect(bar, g);
  painter.setPen(Qt::white);
  const QRectF labels(bar.left(), bar.top() - 16, bar.width(), 14);
  painter.drawText(labels, Qt::AlignLeft, tr("0 px"));
  painter.drawText(labels, Qt::AlignHCenter, tr("residual"));
  painter.drawText(labels, Qt::AlignRight,
                   tr("≥ %1 px").arg(Canvas::kRedResidualPx, 0, 'g', 3));
  painter.restore();
}

void paintMagnifiedResiduals(QPainter& painter, const ViewTransform& view,
                             const Document& document, double factor) {
  if (document.pairs().empty() || document.manualCamera()) return;
  // The residuals are of the geometry (ui/document_fit): the camera's position part.
  const Camera geometry = positionPart(document.camera());
  painter.save();
  for (size_t i = 0; i < document.pairs().size(); ++i) {
    const Pair& p = document.pairs()[i];
    const auto fitted = targetPixelFromSourcePixel(geometry, p.source);
    if (!fitted) continue;
    const Eigen::Vector2d tip = *fitted + factor * (p.target - *fitted);
    const QPointF from = view.widgetFromImage(QPointF(fitted->x(), fitted->y()));
    const QPointF to = view.widgetFromImage(QPointF(tip.x(), tip.y()));
    const QColor colour = p.enabled ? Canvas::residualColour(document.residual(static_cast<int>(i)))
                                    : QColor(150, 150, 150);
    painter.setPen(QPen(QColor(0, 0, 0, 160), 4.0, Qt::SolidLine, Qt::RoundCap));
    painter.drawLine(from, to);
    painter.setPen(QPen(colour, 2.0, Qt::SolidLine, Qt::RoundCap));
    painter.drawLine(from, to);
    painter.setBrush(colour);
    painter.setPen(QPen(Qt::black, 1.0));
    painter.drawEllipse(from, 2.5, 2.5);
  }
  painter.restore();
}

void drawHaloText(QPainter& painter, const QPointF& at, const QString& text, const QColor& fill,
                  const QColor& halo) {
  QPainterPath path;
  path.addText(at, painter.font(), text);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.strokePath(path, QPen(halo, 3.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  painter.fillPath(path, fill);
  painter.restore();
}

}  // namespace artcam::ui
