// SPDX-License-Identifier: Apache-2.0
// The input contract shared by the two depth-of-field blurs (depth_of_field.h): premultiplied
// RGBA and a 1-channel σ image of the same size. A broken contract throws.
#pragma once

#include "core/model/image.h"

#include <stdexcept>

namespace artcam {

inline void checkBlurInputs(const ImageF& rgba, const ImageF& sigma) {
  if (rgba.channels != 4 || rgba.empty())
    throw std::invalid_argument("depth of field needs a 4-channel premultiplied RGBA image");
  if (sigma.channels != 1 || sigma.width != rgba.width || sigma.height != rgba.height)
    throw std::invalid_argument(
        "depth of field: the sigma image must be 1 channel of the "
        "colour image's size");
}

}  // namespace artcam
