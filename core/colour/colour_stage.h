// SPDX-License-Identifier: Apache-2.0
// Putting a fitted colour block into a studio camera (eq 6/7).
//
// The studio's geometry comes from point pairs (or a hand-made camera) and its colour from
// colour samples; the camera the preview and the export render is both at once. A colour
// camera made by core's colourCamera (colour_map.h) has blocks [position (u, v, 1) | colour
// (a·r, a·g, a·b, a)], identity geometry, and colour outputs that read only the colour block
// and the position's homogeneous weight p_3 — which is 1 at every stage's input (eq 5
// re-homogenises between stages). Its colour tensors can therefore be moved into any camera's
// layout by renumbering their rows and columns, whatever that camera's geometry.
#pragma once

#include "core/model/camera.h"

namespace artcam {

// `base` with the colour outputs of its LAST stage replaced by those of `colour` (eq 6/7: the
// cc and pc parts of the colour tensors); earlier stages keep their colour outputs, or pass
// colour through when `base` had no colour block (one is then added right after the position
// block). The position outputs are untouched, so a geometry-only base keeps its kernel class.
// Throws std::invalid_argument when `base` has no 2D position block or `colour` is not a
// one-stage [position 3 | colour 4] camera.
Camera withColourBlock(const Camera& base, const Camera& colour);

// The colour `colour` (a colourCamera) gives an opaque linear RGB; false where it is not
// finite or its weight is not positive (out of the map's domain).
bool applyColourCamera(const Camera& colour, const double rgb[3], double out[3]);

}  // namespace artcam
