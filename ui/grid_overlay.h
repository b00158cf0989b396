// SPDX-License-Identifier: Apache-2.0
// Guides over the canvas picture (View ▸ Show Grid): the rule-of-thirds lines and a finer grid
// of equal divisions of the photo, drawn in the image rectangle in widget coordinates, so the
// grid follows the picture through zoom and pan whatever the canvas shows in it (the photo,
// the depth overlay, a warped result). Each line is a light line over a dark one, so it reads
// on bright and dark areas alike.
#pragma once

#include <QRectF>

class QPainter;

namespace artcam::ui {

struct GridOverlayOptions {
  int divisions = 8;    // the fine grid: this many equal parts of the width and of the height
  bool thirds = true;   // the rule-of-thirds lines, stronger than the fine grid
};

void paintGridOverlay(QPainter& painter, const QRectF& image_rect_widget,
                      const GridOverlayOptions& options = {});

}  // namespace artcam::ui
