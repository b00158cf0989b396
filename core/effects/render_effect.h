// The one render call that applies any image effect's camera (effect_table.h builds them): the
// layers summed (the paper's Fig 4), then the depth-of-field blur when the camera's depth output
// is the blur variance.
#pragma once

#include "core/effects/depth_of_field.h"
#include "core/model/artcam.h"
#include "core/model/image.h"
#include "core/render/attributed.h"

namespace artcam {

// renderLayers, then for DepthOutput::BlurVariance the fast blur stack with σ from the depth
// output. The result's colour is RGBA premultiplied; empty when cancelled (summary->cancelled).
// Throws std::invalid_argument for a piecewise camera: its patches are not layers, and an effect
// never has them.
AttributedImage renderEffect(const ImageF& source, const ImageF* depth, const Artcam& camera,
                             const AttributedOptions& options = {},
                             AttributedSummary* summary = nullptr);

}  // namespace artcam
