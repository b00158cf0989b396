// SPDX-License-Identifier: Apache-2.0
// Fitting a piecewise camera (one step beyond the quadratic; paper §5): split the region the
// matches cover into patches, fit one camera per patch, and subdivide a patch (quadtree) until
// its max error is below a threshold in pixels.
//
// Continuity at the seams: each patch is fitted on the matches inside its rectangle grown by
// a shared margin, so the matches near an edge constrain both neighbours and they agree there;
// the summary measures the remaining disagreement along every shared edge (seam_gap_px).
// Poles matter only inside a patch, so each patch's denominator is checked over its own
// rectangle (exactly, poles.h) rather than over the whole frame.
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/fit_record.h"
#include "core/model/status.h"
#include "core/model/piecewise_camera.h"

#include <string>
#include <vector>

namespace artcam {

struct PiecewiseOptions {
  double max_error_px = 0.5;   // a patch is split while its max residual exceeds this
  int min_matches = 12;        // per patch fit (≥ 9 for the quadratic; a few spare for noise)
  int max_depth = 6;           // quadtree levels below the whole region
  // Fraction of a patch's size whose matches it shares with its neighbours (grown up to 1 for
  // a patch that would otherwise have fewer than min_matches).
  double shared_margin = 0.2;
  ModelClass model = ModelClass::Quadratic;  // per patch (Auto runs the ladder per patch)
  bool refine = true;          // Levenberg–Marquardt per patch
};

struct PiecewiseSummary {
  Status status;  // not ok: no camera (too few matches overall, non-finite input …)
  PiecewiseCamera camera;
  int matches = 0;
  double rms_px = 0.0;  // over all enabled matches, each through its own patch
  double max_px = 0.0;
  double seam_gap_px = 0.0;  // largest disagreement of neighbouring patches on shared edges
  bool converged = true;     // every patch is within max_error_px
  // The single-camera floor on the same matches (one quadratic over everything), for the
  // comparison the report prints; negative when that fit failed.
  double single_rms_px = -1.0;
  double single_max_px = -1.0;
  std::string report() const;  // a few lines for the CLI
};

PiecewiseSummary fitPiecewise(const std::vector<PointMatch>& matches, FrameSize source_size,
                              FrameSize target_size, const PiecewiseOptions& options = {});

// Largest distance (target pixels) between the predictions of patches that share an edge,
// sampled along every shared edge.
double measureSeamGap(const PiecewiseCamera& camera, int samples_per_edge = 17);

}  // namespace artcam
