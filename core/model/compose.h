// SPDX-License-Identifier: Apache-2.0
// Composition of cameras into one (the paper's §5: a canonical view → table
// homography → reflection becomes one camera).
//
// compose(first, second) is the camera x ↦ second(first(x)). first's target frame is second's
// source frame (docs/architecture.md, "Composition"): equal frames meet as they are; frames of
// one shape and another size meet as `warp` would apply second to first's output (second's
// frames scaled per axis, exact, and said in the summary's description); frames of different
// shapes are refused, since the composition would stretch or crop the picture unseen.
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

#include "core/model/artcam.h"
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

namespace artcam {

// compose for whole camera values: x ↦ second(first(x)), layer by layer.
// - Layers: a single camera composes with every layer of a layered one; two layered cameras
//   compose layer k with layer k and must have as many layers. The picture is the sum of the
//   layers' colours and each layer selects its own colour channel, so second_j(first_k(·))
//   vanishes for j ≠ k and the sum of the pairwise compositions is the whole composition.
// - Depth: a chain feeds first's depth output to second's depth input. That is right when first
//   passes depth on unchanged, or when second does not read depth. When first outputs another
//   quantity l = g(d) (aerial perspective's log depth, 0 at its near and 1 at its far depth) and
//   second reads depth only in its depth output h(d) (depth of field's blur variance), a bridge
//   stage maps l to the inverse depth m = 1/g⁻¹(l), fitted as a ratio of quadratics in (l, 1)
//   over [0, 1], and h is read exactly on (m, 1) — the paper's Fig 3 bottom right as one
//   camera, accurate to 1 % of the largest h (else refused, with the error).
//   Anything else that would read the wrong quantity is refused with that reason. Depth of field
//   must come last (its output is a blur variance, not a depth). The result's depth output
//   means what second's does.
// - Patches: a piecewise first composes each patch (and its single-camera fit) with a
//   single-layer position-only second (a homography folds in, anything else chains: exact).
//   A piecewise second takes a single-stage homography first (the paper's §5 canonical view →
//   table → reflection): H folds into each patch camera exactly (Q_i ← Hᵀ Q_i H) and the
//   rectangles stay where they were fitted, reached through the patch frame's homography
//   (piecewise_camera.h), so the patches' regions are H⁻¹ of rectangles exactly; patches no
//   source pixel reaches are left out. Any other camera before patches would bend their
//   regions into curves and is refused, as are two piecewise cameras and colour, depth or
//   layers after patches (the patches are position-only).
// Matches and fit records are dropped: the result was not fitted to anything.
Result<Artcam> composeArtcams(const Artcam& first, const Artcam& second,
                              std::string* description = nullptr);

}  // namespace artcam
