// SPDX-License-Identifier: Apache-2.0
// What the canvas draws to explain the pairs, beside the markers themselves:
// - the residual legend: the marker colour ramp (Canvas::residualColour, green at 0 px through
//   yellow to red at kRedResidualPx and beyond) as a bar with px labels, in the canvas's
//   bottom-right corner (the depth legend has the bottom-left);
// - magnified residuals: for each pair, the vector from where the fitted camera sends its
//   source (the fitted target) to the clicked target, scaled by a factor (×10), so sub-pixel
//   misfits show their direction and their pattern (a missing model term bends them all alike);
// - text with a halo (a dark outline under light text), so pair numbers read on bright areas.
// Widget coordinates throughout; pairs are photo pixels (centres at i + 0.5).
#pragma once

#include <QColor>
#include <QPointF>
#include <QRectF>
#include <QSize>
#include <QString>

class QPainter;

namespace artcam::ui {

class Document;
class ViewTransform;

inline constexpr double kResidualMagnification = 10.0;

// The legend's colour bar in a widget of `size` (the labels sit above it).
QRectF residualLegendBar(const QSize& size);
void paintResidualLegend(QPainter& painter, const QSize& size);

// The magnified residual vectors of every pair whose fitted target is defined.
void paintMagnifiedResiduals(QPainter& painter, const ViewTransform& view,
                             const Document& document, double factor = kResidualMagnification);

// `text` with its baseline starting at `at`, light with a dark halo.
void drawHaloText(QPainter& painter, const QPointF& at, const QString& text,
                  const QColor& fill, const QColor& halo);

}  // namespace artcam::ui
