// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 6 made in code: a silver reflector and a green one, rendered under the same
// lights from the same view, so pixel (x, y) of one and of the other see the same surface point.
// Relighting the silver one as the green one is a colour map that must keep the highlights
// nearly white while turning the rest green — non-linear in the colour, which is what the
// colour block's quadratic forms are for (§4.1).
//
// The scene: an orthographic view of a sphere (radius 0.42 of the image side) over a black
// backdrop, in a room with a blue sky, a red-brown floor and six coloured walls round the
// horizon, lit by one key light. Silver is almost all mirror, untinted; the bauble is a green
// glaze: its reflection of the room tinted green, a little green body colour. Both show the key
// light's highlight, three times brighter than the room and clipped at 1 per channel as in a
// photo. 3 × 3 supersampled; colours are linear light (sRGB primaries), opaque, 3 channels.
#pragma once

#include "core/model/fit_record.h"
#include "core/model/image.h"

#include <vector>

namespace artcam {

struct SpecularPair {
  ImageF silver;  // the coffee pot's surface
  ImageF green;   // the bauble's, the truth the relit silver is measured against
  // Where the sphere covers the pixel fully (all nine subsamples on it): the pixels a ΔE
  // measure is about; row-major, width × height.
  std::vector<unsigned char> on_object;
};

SpecularPair makeSpecularPair(int size);

// Colour samples (linear RGB, silver → green) at every `stride`-th pixel in x and y that is
// fully on the object, and one of the (black) backdrop.
std::vector<PointMatch> specularSamples(const SpecularPair& pair, int stride);

}  // namespace artcam
