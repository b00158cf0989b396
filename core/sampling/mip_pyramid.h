// SPDX-License-Identifier: Apache-2.0
// A mip pyramid of a source photo for previews: built once per photo,
// so a screen-sized preview of a 24-megapixel photo samples a level near its own resolution
// instead of aliasing through (or supersampling) the full-size image.
//
// Conventions: level 0 is the photo; level k + 1 averages 2×2 blocks of level k (premultiplied
// colour, so averaging is correct with alpha), its size ⌈w/2⌉ × ⌈h/2⌉ with the last row or
// column repeated when odd. Cameras live in normalised frames (frames.h), so any level can be
// warped by the same camera; an odd size shifts a level by at most half of one of its pixels.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/model/pixel_buffer.h"

#include <vector>

namespace artcam {

class MipPyramid {
 public:
  // Levels down to `min_size` pixels on the longer side.
  explicit MipPyramid(ImageF base, int min_size = 64);

  int levels() const { return static_cast<int>(levels_.size()); }
  const ImageF& level(int k) const { return levels_[static_cast<size_t>(k)]; }
  // The coarsest level whose pixels are no larger than `footprint` level-0 pixels: the level
  // to sample when one output pixel covers `footprint` source pixels.
  int levelFor(double footprint) const;

 private:
  std::vector<ImageF> levels_;
};

// The 8-bit twin for interactive previews: levels of the stored
// (display-encoded) samples of an RGB or RGBA photo, each a 2×2 box average rounded to nearest
// (premultiplied alpha averages correctly; averaging encoded values instead of linear light is
// a preview's approximation). Level 0 is the caller's image, viewed, not copied: it must
// outlive the pyramid. Levels down to `min_size` pixels on the longer side.
class StoredMipPyramid {
 public:
  explicit StoredMipPyramid(const ConstImageView& base, int min_size = 64);

  int levels() const { return static_cast<int>(views_.size()); }
  const ConstImageView& level(int k) const { return views_[static_cast<size_t>(k)]; }
  int levelFor(double footprint) const;

 private:
  std::vector<PixelBuffer> owned_;  // levels 1 …
  std::vector<ConstImageView> views_;
};

}  // namespace artcam
