// SPDX-License-Identifier: Apache-2.0
// The depth-coverage rule: how an effect driven by depth meets the soft edge of a painted mask.
//
// The depth input is the homogeneous block (c·d, c) (core/depth/depth_raster.h; a 1-channel
// depth file has c = 1 where it holds a depth and 0 in its holes): c is how much of the pixel
// the painted layers cover. An effect driven by depth — aerial perspective's haze, depth of
// field's blur — acts on a pixel in proportion to c, on premultiplied RGBA:
//
//     out = c·effect + (1 − c)·untouched
//
// so c = 0 keeps the pixel as it was (nobody gave it a depth), c = 1 is the whole effect, and a
// brush's soft fringe fades the effect in exactly as smoothly as its coverage. The effect
// itself is evaluated at the depth the fringe carries (the covered texels' depth), never at a
// depth scaled by c: a plane's depth is bounded by its own points (inverse_depth_plane.h), so
// the fringe has the depth of the surface it belongs to and only the amount of effect fades.
//
// One rule, two places that apply it: the haze per pixel as the camera is evaluated
// (core/render/attributed.cpp, the colour-only and gather paths), the blur — which needs the
// neighbourhood — after the blur stack (core/pipeline/render.cpp), from the coverage the
// renderer hands back (AttributedImage::depth_coverage).
#pragma once

#include "core/model/image.h"

namespace artcam {

// One pixel: `effect` (4 floats, premultiplied RGBA) becomes c·effect + (1 − c)·untouched.
// c ≥ 1 leaves it, c ≤ 0 makes it `untouched` exactly.
inline void fadeByDepthCoverage(float coverage, const float* untouched, float* effect) {
  if (coverage >= 1.0f) return;
  if (!(coverage > 0.0f)) {
    for (int k = 0; k < 4; ++k) effect[k] = untouched[k];
    return;
  }
  for (int k = 0; k < 4; ++k) effect[k] = coverage * effect[k] + (1.0f - coverage) * untouched[k];
}

// Images: `effect` and `untouched` RGBA (4 channels) of one size, `coverage` 1 channel of that
// size; bands of rows on `threads` (0: every core). Throws std::invalid_argument when the sizes
// disagree.
void fadeByDepthCoverage(const ImageF& coverage, const ImageF& untouched, ImageF& effect,
                         int threads = 0);

}  // namespace artcam
