// SPDX-License-Identifier: Apache-2.0
// The approximate inverse camera that seeds the per-pixel Newton of the rational kernel
// (an inverse camera fitted to the forward map).
//
// The forward map is sampled on a grid over the source frame; samples on the centre's side of
// every pole curve and in the centre's fold become matches target → source (roles swapped),
// and the fitting room fits a full quadratic camera to them (fit_image.h). The
// inverse of a rational map is not rational, so this is only a start: Newton refines it and
// the residual test decides.
#pragma once

#include "core/model/status.h"
#include "core/mapping/rational_map.h"

namespace artcam {

struct InverseSeedOptions {
  int grid = 16;  // samples per side of the source frame
};

// output pixels → source pixels; a failure says why (too few usable samples, degenerate fit).
Result<RationalMap> fitInverseSeed(const RationalMap& forward, FrameSize source_px,
                                   FrameSize target_px, const InverseSeedOptions& options = {});

}  // namespace artcam
