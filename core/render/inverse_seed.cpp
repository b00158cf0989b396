#include "core/render/inverse_seed.h"

namespace artcam {

// Placeholder until the fitting room (core/fit/fit_image.cpp) lands.
Result<RationalMap> fitInverseSeed(const RationalMap&, FrameSize, FrameSize,
                                   const InverseSeedOptions&) {
  return Result<RationalMap>::failure("the inverse seed fit is not available yet");
}

}  // namespace artcam
