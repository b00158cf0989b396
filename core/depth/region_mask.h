// SPDX-License-Identifier: Apache-2.0
// A painted region of a photo: one coverage byte per photo pixel (0 = outside, 255 = inside),
// so brushes can have soft edges. Pixel (x, y) covers [x, x+1)×[y, y+1); its centre is
// (x + 0.5, y + 0.5), as everywhere in the engine. Positions passed here are photo PIXELS in
// that convention.
//
// Decisions:
// - Painting keeps the larger coverage (max), erasing the smaller of (old, 255 − dab): dabs
//   along a stroke overlap, and max/min keeps a slow stroke from building up darker than one
//   dab, as an artist expects from a mask brush.
// - A brush dab of radius r and hardness h is fully opaque out to h·r and falls off smoothly
//   (smoothstep) to 0 at r. Hardness 1 is a hard disc of pixel centres within r.
// - A polygon covers the pixels whose CENTRES lie inside it (even–odd rule), hard-edged.
// - Every edit reports the rectangle it touched, so undo commands store only that rectangle
//   before and after (a full-resolution mask is one byte per photo pixel).
#pragma once

#include "core/model/status.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace artcam {

// Half-open pixel rectangle [x0, x1) × [y0, y1); empty when x1 <= x0 or y1 <= y0.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return empty() ? 0 : x1 - x0; }
  int height() const { return empty() ? 0 : y1 - y0; }
  PixelRect united(const PixelRect& o) const;
  bool operator==(const PixelRect&) const = default;
};

// The pixels one dab may change: `allowed` holds a byte per pixel of `rect`, row by row,
// non-zero where the dab may paint (edge_aware_brush.h makes it).
struct DabLimit {
  PixelRect rect;
  std::vector<uint8_t> allowed;
  bool allows(int x, int y) const {
    if (x < rect.x0 || y < rect.y0 || x >= rect.x1 || y >= rect.y1) return false;
    return allowed[static_cast<size_t>(y - rect.y0) * static_cast<size_t>(rect.width()) +
                   static_cast<size_t>(x - rect.x0)] != 0;
  }
};

struct BrushOptions {
  double radius = 20.0;   // photo pixels
  double hardness = 0.7;  // [0, 1]: share of the radius that is fully opaque
  bool erase = false;
};

class RegionMask {
 public:
  RegionMask() = default;
  RegionMask(int width, int height);  // all outside

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }
  PixelRect bounds() const { return {0, 0, width_, height_}; }
  uint8_t at(int x, int y) const { return coverage_[index(x, y)]; }
  const std::vector<uint8_t>& coverage() const { return coverage_; }
  bool operator==(const RegionMask&) const = default;

  // One dab centred at `centre`. Returns the pixels it may have changed (clipped).
  // With `limit`, only the pixels it allows.
  PixelRect stamp(const Eigen::Vector2d& centre, const BrushOptions& brush,
                  const DabLimit* limit = nullptr);
  // The pixels a dab of `radius` at `centre` may touch (pixel centres within the radius can
  // lie only there), clipped to the mask.
  PixelRect dabRect(const Eigen::Vector2d& centre, double radius) const;
  // Dabs from `from` to `to` every quarter radius (at least every pixel), `from` excluded:
  // a stroke is stamp(first) then segment(previous, next) per mouse move.
  PixelRect segment(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                    const BrushOptions& brush);
  // Fills (or with `erase`, clears) the pixels whose centres are inside the closed polygon.
  PixelRect fillPolygon(const std::vector<Eigen::Vector2d>& vertices, bool erase = false);

  // The bytes of `rect` (row by row) and their reverse; undo stores these.
  std::vector<uint8_t> copyRect(const PixelRect& rect) const;
  void pasteRect(const PixelRect& rect, const std::vector<uint8_t>& bytes);

  // Number of pixels with coverage > 0.
  size_t coveredCount() const;

 private:
  size_t index(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
  }
  PixelRect clip(const PixelRect& r) const;

  int width_ = 0;
  int height_ = 0;
  std::vector<uint8_t> coverage_;
};

// Compact bytes for files: runs of equal coverage as (value byte, LEB128 length). A painted
// mask is mostly long runs of 0 and 255, so it shrinks by orders of magnitude.
std::vector<uint8_t> encodeMaskRuns(const RegionMask& mask);
// `where` names the file place in messages. Refuses runs that do not add up to width×height.
Result<RegionMask> decodeMaskRuns(const std::vector<uint8_t>& bytes, int width, int height,
                                  const std::string& where);

}  // namespace artcam
