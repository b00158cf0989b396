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
//
// Between the matches (docs/architecture.md). A patch that meets the threshold at its matches can still
// bend between them (a quadratic has 17 degrees of freedom; a patch of a dozen matches nearly
// interpolates them). So a patch is accepted only when its HELD-OUT error meets the threshold
// too: its own matches are dealt into five folds, each predicted by the patch fitted without
// it (same ladder, same pole check); a grid point left out is a point between its neighbours.
// The truth between matches is unknown to a fit from matches, so this is the measure: a cell
// splits while either error exceeds the threshold, and a patch that cannot split further keeps
// both errors in its report (within_tolerance false).
//
// The frame. Patches tile the source frame, so matches outside it are refused before fitting
// (outside_frame_px). A grid of samples at pixel centres stops short of the frame's edges by up
// to a step, so the tiling's outer edges are put on the frame's edges when they stop within
// snap_to_frame_px of them, as far as the outer patches are trusted beyond their matches anyway;
// every rectangle is clipped to the frame.
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
  // Matches whose source lies further than this outside the source frame are refused before
  // the fit (a caller that samples a map beyond the frame on purpose, core/lens, passes more).
  double outside_frame_px = 1.0;
  // Outer edges of the tiling within this of the frame's edges are moved onto them; negative:
  // the camera's support margin (1.5 match spacings).
  double snap_to_frame_px = -1.0;
};

struct PiecewiseSummary {
  Status status;  // not ok: no camera (too few matches overall, non-finite input …)
  // ≥ 0: the threshold asked for more than kMaxPatches (artcam.h), so the quadtree was grown
  // only to this depth (below options.max_depth); some patches then miss the threshold.
  int patch_limited_depth = -1;
  PiecewiseCamera camera;
  int matches = 0;
  double rms_px = 0.0;  // over all enabled matches, each through its own patch
  double max_px = 0.0;
  // The largest held-out residual of any patch (see above): the error the fit stands behind
  // between its matches.
  double held_out_max_px = 0.0;
  double seam_gap_px = 0.0;  // largest disagreement of neighbouring patches on shared edges
  bool converged = true;     // every patch is within max_error_px, at and between its matches
  // The single-camera floor on the same matches (one quadratic over everything), for the
  // comparison the report prints; negative when that fit failed.
  double single_rms_px = -1.0;
  double single_max_px = -1.0;
  std::string report() const;  // a few lines for the CLI
};

// The report's words for patch_limited_depth ("; the tree stops at depth 5: …").
std::string patchLimitNote(int depth);

PiecewiseSummary fitPiecewise(const std::vector<PointMatch>& matches, FrameSize source_size,
                              FrameSize target_size, const PiecewiseOptions& options = {});

// Largest distance (target pixels) between the predictions of patches that share an edge,
// sampled along every shared edge.
double measureSeamGap(const PiecewiseCamera& camera, int samples_per_edge = 17);

}  // namespace artcam
