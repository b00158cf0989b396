// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/graphic_placement.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

ImageF placeGraphic(const ImageF& graphic, FrameSize board, const GraphicPlacement& placement) {
  if (placement.fillsBoard() || graphic.empty() || !board.isImage()) return graphic;
  // Placed-image pixels per board pixel: the graphic's own resolution, capped.
  double r = graphic.width / placement.width;
  r = std::min(r, static_cast<double>(kMaxPlacedSide) / std::max(board.width, board.height));
  const int w = std::max(1, static_cast<int>(std::lround(board.width * r)));
  const int h = std::max(1, static_cast<int>(std::lround(board.height * r)));
  const int channels = graphic.alpha_channel >= 0 ? graphic.channels : graphic.channels + 1;
  ImageF out(w, h, channels, channels - 1);  // premultiplied, transparent black
  // Graphic pixels per placed pixel, and the graphic's top-left in placed pixels.
  const double k = graphic.width / (placement.width * r);
  const double ox = placement.origin.x() * r, oy = placement.origin.y() * r;
  const double gh = placement.width * graphic.height / graphic.width * r;  // height, placed px
  const int x0 = std::max(0, static_cast<int>(std::floor(ox))),
            x1 = std::min(w, static_cast<int>(std::ceil(ox + placement.width * r)));
  const int y0 = std::max(0, static_cast<int>(std::floor(oy))),
            y1 = std::min(h, static_cast<int>(std::ceil(oy + gh)));
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      // Graphic coordinates of this pixel's centre; outside the graphic stays transparent.
      const double gx = (x + 0.5 - ox) * k, gy = (y + 0.5 - oy) * k;
      if (gx < 0.0 || gy < 0.0 || gx > graphic.width || gy > graphic.height) continue;
      const double fx = std::clamp(gx - 0.5, 0.0, graphic.width - 1.0);
      const double fy = std::clamp(gy - 0.5, 0.0, graphic.height - 1.0);
      const int ix = std::min(static_cast<int>(fx), graphic.width - 1);
      const int iy = std::min(static_cast<int>(fy), graphic.height - 1);
      const int jx = std::min(ix + 1, graphic.width - 1), jy = std::min(iy + 1, graphic.height - 1);
      const double tx = fx - ix, ty = fy - iy;
      float* o = out.pixel(x, y);
      const float* a = graphic.pixel(ix, iy);
      const float* b = graphic.pixel(jx, iy);
      const float* c = graphic.pixel(ix, jy);
      const float* d = graphic.pixel(jx, jy);
      for (int ch = 0; ch < graphic.channels; ++ch) {
        const double v =
            (1 - ty) * ((1 - tx) * a[ch] + tx * b[ch]) + ty * ((1 - tx) * c[ch] + tx * d[ch]);
        o[ch] = static_cast<float>(v);
      }
      if (graphic.alpha_channel < 0) o[channels - 1] = 1.0f;
    }
  return out;
}

}  // namespace artcam::ui
