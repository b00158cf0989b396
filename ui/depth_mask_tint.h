// SPDX-License-Identifier: Apache-2.0
// A region mask as a translucent tint to draw over the photo: `colour` at coverage/255 of
// kMaskTintOpacity, reduced so its long side is at most `max_side` (aspect kept; each tint
// pixel reads the mask pixel under its centre, as depth_raster.h reads masks).
#pragma once

#include "core/depth/region_mask.h"

#include <QColor>
#include <QImage>

namespace artcam::ui {

inline constexpr double kMaskTintOpacity = 0.45;

QImage maskTint(const RegionMask& mask, const QColor& colour, int max_side);

}  // namespace artcam::ui
