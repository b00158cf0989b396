// SPDX-License-Identifier: Apache-2.0
// What Insertion mode draws over the canvas's photo, in widget coordinates: the live
// composite (the graphic through the piecewise camera over the photo), the per-patch error
// map, the marked region and the grid matches. Painted by the grid and region tools
// (Tool::paint), so the canvas needs no hook of its own.
#pragma once

#include <QColor>

class QPainter;

namespace artcam::ui {

class InsertionModel;
class InsertionPreview;
class ViewTransform;

class InsertionOverlay {
 public:
  // Green at 0 px through yellow to red at ≥ max_error_px.
  static QColor errorColour(double error_px, double max_error_px);

  static void paint(QPainter& painter, const ViewTransform& view, const InsertionModel& model,
                    const InsertionPreview& preview);
};

}  // namespace artcam::ui
