// SPDX-License-Identifier: Apache-2.0
// Where the graphic sits on the board's canonical view (board pixels). By default it fills the
// whole view (stretched to it, as `artcam insert` does); a placement puts it at `origin` with
// `width` board pixels and its own aspect ratio, transparent elsewhere.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"

#include <Eigen/Core>

namespace artcam::ui {

struct GraphicPlacement {
  Eigen::Vector2d origin{0.0, 0.0};  // top-left corner, board pixels
  double width = 0.0;                // board pixels; ≤ 0: fill the whole board

  bool fillsBoard() const { return !(width > 0.0); }
  bool operator==(const GraphicPlacement&) const = default;
};

// The source image to render through the board → photo camera: the graphic itself when it
// fills the board, else a transparent board-shaped image holding the graphic at its place,
// at the graphic's own resolution (capped at kMaxPlacedSide), sampled bilinearly at pixel
// centres (so an aligned placement copies the graphic's pixels exactly).
inline constexpr int kMaxPlacedSide = 4096;
ImageF placeGraphic(const ImageF& graphic, FrameSize board, const GraphicPlacement& placement);

}  // namespace artcam::ui
