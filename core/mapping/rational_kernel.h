// SPDX-License-Identifier: Apache-2.0
// The coordinate kernel of a rational (non-projective) position camera, for makeCoordinateKernel
// (coordinates.h) alone. Where the map is smooth enough, cells of 64 × 64 pixels are certified
// against the forward map and their pixels come from one cubic patch each (inverse_cells.h);
// elsewhere each pixel starts from the fitted inverse seed (inverse_seed.h), is checked by one
// forward evaluation and refined by Newton (inverse.h) only where the check fails.
#pragma once

#include "core/mapping/coordinates.h"
#include "core/mapping/rational_map.h"
#include "core/model/frames.h"

#include <memory>
#include <optional>

namespace artcam {

std::unique_ptr<CoordinateKernel> makeRationalKernel(RationalMap forward, std::optional<RationalMap> seed,
                                                     FrameSize source_px, FrameSize target_px,
                                                     const CoordinateOptions& options, int threads);

}  // namespace artcam
