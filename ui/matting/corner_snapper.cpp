// SPDX-License-Identifier: Apache-2.0
// The studio's corner snap: core's checkerboard X-corner finder, searching as far as a click
// can be off (kSnapRadiusWidgetPx on screen, so zooming in narrows it to the corner the user
// means where reflected squares are only a few photo pixels wide).
#include "core/piecewise/corner_snap.h"
#include "ui/matting/insertion_studio.h"

#include <algorithm>

namespace artcam::ui {

CornerSnapper defaultCornerSnapper() {
  return [](const ImageF& photo, const Eigen::Vector2d& click, double search_radius_px) {
    CornerSnapOptions options;
    options.search_radius_px = std::clamp(search_radius_px, 1.0, 8.0);
    options.window_radius_px = std::clamp(1.2 * options.search_radius_px, 2.5, 5.0);
    return snapToGridCorner(photo, click, options);
  };
}

}  // namespace artcam::ui
