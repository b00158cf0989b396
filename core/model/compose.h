// Composition of cameras into one (the paper's §5: a canonical view → table
// homography → reflection becomes one camera).
//
// compose(first, second) is the camera x ↦ second(first(x)). Pixels are the common currency
// between the two: first's target pixel is second's source pixel, so when the frame sizes
// differ the change between the two normalised frames (a scale and shift) is folded in.
//
// What comes out, cheapest first:
// - second is a homography A (position only, one stage): A mixes first's last-stage outputs,
//   Q'_i = Σ_j A_ij Q_j (the output-side rule). Exact for any first camera.
// - first is a homography H (position only, one stage): substituting x ← x Hᵀ gives the
//   input-side rule Q_i ← H_row Q_i H_rowᵀ with H_row = Hᵀ. A projective H changes the
//   position block's homogeneous weight, which cancels in eq 5 only because every output is
//   then a form in position alone; cameras with colour or depth blocks are chained instead.
// - anything else: a chain, first's stages then second's (the frame change folded into
//   second's first stage, where it is affine and so exact).
#pragma once

#include "core/model/camera.h"
#include "core/model/status.h"

#include <string>

namespace artcam {

enum class CompositionKind { OutputHomography, InputHomography, Chain };

struct CompositionSummary {
  CompositionKind kind = CompositionKind::Chain;
  int stages = 0;
  std::string description;  // one line for the CLI, e.g. "folded the homography into …"
};

// Fails (with the cause) when the blocks differ or the frames cannot meet: an image target
// fed to an object-space source or the reverse.
Result<Camera> composeCameras(const Camera& first, const Camera& second,
                              CompositionSummary* summary = nullptr);

}  // namespace artcam
