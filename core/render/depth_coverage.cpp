// SPDX-License-Identifier: Apache-2.0
#include "core/render/depth_coverage.h"

#include "core/util/parallel.h"

#include <stdexcept>

namespace artcam {

void fadeByDepthCoverage(const ImageF& coverage, const ImageF& untouched, ImageF& effect,
                         int threads) {
  if (effect.channels != 4 || untouched.channels != 4 || coverage.channels != 1 ||
      effect.width != untouched.width || effect.height != untouched.height ||
      coverage.width != effect.width || coverage.height != effect.height)
    throw std::invalid_argument(
        "fadeByDepthCoverage: the effect, the untouched image (RGBA) and the coverage (1 channel) "
        "must have one size");
  const size_t w = static_cast<size_t>(coverage.width);
  ParallelOptions parallel;
  parallel.threads = threads;
  parallel.band_rows = 64;
  parallelForRows(coverage.height, parallel, [&](int y0, int y1) {
    for (size_t i = static_cast<size_t>(y0) * w; i < static_cast<size_t>(y1) * w; ++i)
      fadeByDepthCoverage(coverage.data[i], untouched.data.data() + 4 * i,
                          effect.data.data() + 4 * i);
  });
}

}  // namespace artcam
