// SPDX-License-Identifier: Apache-2.0
// Colour calibration (the paper's §4.1): fit a colour
// transform to colour-sample pairs, choosing its complexity by held-out error ("colour
// constancy by model selection", [LH07]), and report CIEDE2000 ΔE per sample and overall.
//
// Samples are PointMatch with 3 numbers per side, LINEAR-light RGB (colour_difference.h;
// matches_csv.h reads them from CSV). Every candidate is fitted by SVD:
// - linear, affine, root-polynomial: linear least squares in the model's terms, columns
//   conditioned first (affine: centroid to the origin, RMS √3, as for geometry; linear and
//   root-polynomial: each column scaled to unit RMS, which keeps the origin where it is);
// - quadratic: the paper's §4 DLT on the colour block — the same solver as 3D positions
//   (fit_image.h, conditioned on both sides, degeneracies refused with their cause). Its
//   denominator must keep one sign over the colour box (the unit cube and every sample): a
//   colour map with a pole is refused like a camera with a pole in its frame.
//
// Selection (`auto`): K-fold held-out mean ΔE00 (leave-one-out up to 10 samples), the simplest
// model whose held-out error a richer one does not beat by options.auto_improvement. Held-out
// errors below 1e-6 ΔE count as exact.
//
// Decision on root-polynomial (not a quadratic form, colour_map.h): it takes part in the
// selection so the user sees whether it would do better, but the map returned — the one an
// ARTcam can hold — is always the best REPRESENTABLE model by the same rule; the summary says
// when root-polynomial won. Asking for it by name fits it and reports it (`stored` is then
// false); the CLI refuses to write it.
//
// Robust option, as for geometry (robust.h): MSAC over minimal sets of the requested model
// with local re-fits, inliers by ΔE00 below the threshold; then the selection on the inliers.
// Auto samples affine minimal sets (4 samples) and re-fits affine and quadratic maps on the
// inliers in the local optimisation (fit_colour.cpp says why).
#pragma once

#include "core/colour/colour_map.h"
#include "core/fit/options_check.h"
#include "core/model/fit_record.h"
#include "core/model/status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace artcam {

struct ColourFitOptions {
  ColourModel model = ColourModel::Auto;
  double auto_improvement = 0.9;
  bool diagnostics = true;  // held-out error of a named model too
  bool robust = false;
  double robust_threshold_de = 3.0;  // ΔE00: a sample is an inlier below this
  double robust_confidence = 0.999;
  int robust_max_iterations = 10000;
  std::uint64_t robust_seed = 20261122;

  // The ranges (options_check.h): model one of the colour models, auto_improvement and
  // robust_confidence in (0, 1], robust_threshold_de finite and above 0, robust_max_iterations
  // 1..10000000. ok, or a failure naming the first field outside its range; fitColourSamples
  // returns that failure without fitting.
  Status check(const FieldNames& names = {}) const;
};

struct ColourCandidate {
  ColourModel model = ColourModel::Linear;
  bool fitted = false;
  std::string failure;          // why not, when !fitted
  double mean_de = -1.0;        // on the samples it was fitted to
  double held_out_de = -1.0;    // K-fold mean ΔE00; -1: not computable (too few samples)
};

struct ColourFitSummary {
  Status status;                 // not ok: no map; the message says why and what would help
  ColourMap map;                 // the fitted map (the stored one for auto)
  bool stored = true;            // map is a quadratic form (an ARTcam can hold it)
  ColourModel selected = ColourModel::Linear;  // auto: the winner, root-polynomial possibly
  std::vector<double> delta_e;   // CIEDE2000 of map(source) against target, per enabled sample
  double mean_de = 0.0, median_de = 0.0, max_de = 0.0;
  double rms_rgb = 0.0;          // RMS of the linear-RGB residual vectors' lengths
  double held_out_de = -1.0;     // of the returned map's model
  std::vector<ColourCandidate> candidates;  // auto: every model tried, simplest first
  std::vector<int> inliers;      // robust: indices into the enabled samples
  std::string reason;            // one line: why this model
  std::string report() const;    // one line: model, samples, ΔE mean / median / max
  // For the .artcam file: residuals_px, rms_px and max_px hold ΔE00 (the reason says so).
  FitRecord record() const;
};

ColourFitSummary fitColourSamples(const std::vector<PointMatch>& samples,
                                  const ColourFitOptions& options = {});

}  // namespace artcam
