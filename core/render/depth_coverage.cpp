// SPDX-License-Identifier: Apache-2.0
#include "core/render/depth_coverage.h"

#include <stdexcept>

namespace artcam {

void fadeByDepthCoverage(const ImageF& coverage, const ImageF& untouched, ImageF& effect) {
  if (effect.channels != 4 || untouched.channels != 4 || coverage.channels != 1 ||
      effect.width != untouched.width || effect.height != untouched.height ||
      coverage.width != effect.width || coverage.height != effect.height)
    throw std::invalid_argument(
        "fadeByDepthCoverage: the effect, the untouched image (RGBA) and the coverage (1 channel) "
        "must have one size");
  const size_t n = coverage.data.size();
  for (size_t i = 0; i < n; ++i)
    fadeByDepthCoverage(coverage.data[i], untouched.data.data() + 4 * i, effect.data.data() + 4 * i);
}

}  // namespace artcam
