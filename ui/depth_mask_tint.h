// SPDX-License-Identifier: Apache-2.0
// A region mask as a translucent tint to draw over the photo: `colour` at coverage/255 of
// kMaskTintOpacity, reduced so its long side is at most `max_side` (aspect kept; each tint
// pixel reads the mask pixel under its centre, as depth_raster.h reads masks).
#pragma once

#include "core/depth/region_mask.h"
#include "core/model/camera.h"

#include <QColor>
#include <QImage>

#include <Eigen/Core>

#include <vector>

namespace artcam::ui {

inline constexpr double kMaskTintOpacity = 0.45;

QImage maskTint(const RegionMask& mask, const QColor& colour, int max_side);

// The tint's size for a mask of that size: the mask's aspect, its long side at most `max_side`.
FrameSize maskTintSize(const RegionMask& mask, int max_side);

// The tint over the warped result: a `grid`-sized raster over the result frame whose pixel k
// shows the mask at photo pixel `photo_px[k]` (NaN: no photo pixel, transparent), so the tint
// lies where the result shows the masked pixels.
QImage maskTintThrough(const RegionMask& mask, const QColor& colour, FrameSize grid,
                       const std::vector<Eigen::Vector2f>& photo_px);

}  // namespace artcam::ui
