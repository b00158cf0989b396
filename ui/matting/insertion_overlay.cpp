// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_overlay.h"

#include "ui/document.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_preview.h"
#include "ui/view_transform.h"

#include <QPainter>
#include <QPainterPath>
#include <QPen>
#include <QPolygonF>

#include <algorithm>

namespace artcam::ui {

QColor InsertionOverlay::errorColour(double error_px, double max_error_px) {
  const double t = max_error_px > 0.0 ? std::clamp(error_px / max_error_px, 0.0, 1.0) : 1.0;
  // Green → yellow over the first half, yellow → red over the second.
  const int r = t < 0.5 ? static_cast<int>(255 * 2 * t) : 255;
  const int g = t < 0.5 ? 200 : static_cast<int>(200 * (2 - 2 * t));
  return QColor(r, g, 0);
}

void InsertionOverlay::paint(QPainter& painter, const ViewTransform& view,
                             const InsertionModel& model, const InsertionPreview& preview) {
  const PhotoPtr& photo = model.document()->photo();
  if (!photo) return;
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  const QRectF photo_rect(0, 0, photo->size().width, photo->size().height);
  if (!preview.composite().isNull()) {
    painter.setRenderHint(QPainter::SmoothPixmapTransform, view.scale() < 1.0);
    painter.drawImage(view.widgetFromImage(photo_rect), preview.composite());
  }
  const QTransform to_widget = view.widgetFromImageTransform();
  const InsertionState& s = model.state();

  if (model.errorMapVisible() && preview.fit().ok) {
    const InsertionFit& fit = preview.fit();
    for (int i = 0; i < fit.patch_outlines.size(); ++i) {
      const QColor c = errorColour(fit.patch_max_px[i], s.max_error_px);
      QColor fill = c;
      fill.setAlpha(60);
      painter.setPen(QPen(c, 1.5));
      painter.setBrush(fill);
      painter.drawPolygon(to_widget.map(fit.patch_outlines[i]));
    }
  }

  if (s.region.size() >= 2) {
    QPolygonF region;
    for (const Eigen::Vector2d& p : s.region) region << QPointF(p.x(), p.y());
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(QColor(0, 200, 255), 2.0, Qt::DashLine));
    if (s.region.size() >= 3)
      painter.drawPolygon(to_widget.map(region));
    else
      painter.drawPolyline(to_widget.map(region));
  }

  painter.setBrush(Qt::NoBrush);
  for (size_t k = 0; k < s.matches.size(); ++k) {
    const QPointF w = view.widgetFromImage(QPointF(s.matches[k].photo.x(), s.matches[k].photo.y()));
    const bool selected = static_cast<int>(k) == model.selectedMatch();
    // Table clicks (the homography's) in cyan, matches through the object in magenta.
    const QColor kind = s.matches[k].on_table ? QColor(0, 220, 255) : QColor(255, 0, 200);
    painter.setPen(QPen(selected ? QColor(255, 255, 0) : kind, selected ? 2.0 : 1.0));
    const double r = selected ? 5.0 : 3.0;
    painter.drawLine(w - QPointF(r, r), w + QPointF(r, r));
    painter.drawLine(w - QPointF(r, -r), w + QPointF(r, -r));
  }
  painter.restore();
}

}  // namespace artcam::ui
