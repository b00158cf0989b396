// SPDX-License-Identifier: Apache-2.0
// The camera that corrects (or simulates) a lens of the lensfun database at a focal length:
// lensfun's modifier is sampled into a dense map and that map is fitted the way `artcam fit
// --stmap` fits one (core/fit for a single camera, core/piecewise beyond it), so there is one
// fitter, not a second one for lenses.
//
// Conventions. The camera's source is the photo as shot and its target the corrected photo
// (`distort`: the reverse, source the clean picture, target one that looks shot through the
// lens). Both frames have the photo's size. lensfun's modifier runs with its own
// normalisation (lfModifier(lens, crop, width, height): the lens's calibration crop against
// the camera's crop, its aspect ratio and centre shift), scale 1 (no zoom to hide the empty
// corners), distortion corrected and the projection converted to rectilinear (a fisheye
// becomes a rectilinear picture; for a rectilinear lens that step is the identity).
// lensfun's pixel (i, j) is the pixel centre, artcam's (i + 0.5, j + 0.5) (docs/architecture.md,
// "Frames and pixels"); lensfun computes in float, about 1e-3 px at 6000 px.
//
// The check. The camera is compared with lensfun's own coordinates on a grid denser than the
// fit's (check_samples along the longer side, the frame's edge pixels included): the largest
// distance, in target pixels, between where the camera sends lensfun's source point and the
// target pixel it came from. Within max_error_px the single camera is kept; otherwise a
// piecewise camera is fitted with that threshold and checked the same way (on the points whose
// source lies in the frame: a piecewise camera has no patches outside it).
//
// Transverse chromatic aberration, where the database has it, makes the camera three layers
// (red, green, blue; core/effects/chromatic.h's block layout), each fitted to lensfun's
// subpixel coordinates of its channel. A piecewise camera cannot be layered (validateArtcam),
// so a lens that needs patches gets its geometry and a note saying TCA was left out.
//
// Vignetting, where the database has it and the aperture is given (lensfun interpolates its
// calibration over focal length, aperture and distance), is a radial gain on colour in the
// same camera (core/lens/vignetting.h: a three-stage chain per layer), fitted to lensfun's own
// colour modifier (lfModifier::ApplyColorModification) sampled at the fit grid's source points
// and checked on the check grid, in percent. Correcting, the gain lensfun applies to the photo
// as shot at the source point; simulating, the one it applies at the target pixel. A piecewise
// camera's patches are position-only, so a lens that needs patches leaves vignetting out, said.
#pragma once

#include "core/lens/lens_database.h"
#include "core/lens/vignetting.h"
#include "core/model/artcam.h"
#include "core/model/status.h"

#include <string>
#include <vector>

namespace artcam {

struct LensCameraOptions {
  std::string lens;            // the lens's model name (LensDatabase::find)
  double focal_mm = 0.0;       // required: the focal length the photo was taken at
  double crop = 0.0;           // the camera's crop factor; 0: the lens's calibration crop
  FrameSize size;              // the photo's size in pixels
  bool distort = false;        // simulate the lens instead of correcting it
  bool tca = true;             // layers per colour channel where the database has TCA
  bool vignetting = true;      // the gain, where the database has it and aperture > 0
  double aperture = 0.0;       // f-number the photo was taken at; 0: not known (no vignetting)
  double distance_m = 1000.0;  // focus distance, metres (vignetting varies a little with it)
  double max_error_px = 0.5;   // single camera up to this, piecewise beyond it
  int fit_samples = 64;        // fit grid, along the longer side (the piecewise fit doubles it)
  int check_samples = 241;     // check grid, along the longer side
};

struct LensCameraSummary {
  Status status;  // not ok: no camera (unknown lens, focal out of range, no calibration …)
  Artcam camera;
  LensEntry lens;
  double crop = 0.0;
  double focal_mm = 0.0;
  // The single camera against lensfun over the check grid, target pixels.
  double single_rms_px = -1.0;
  double single_max_px = -1.0;
  // The camera returned (single or piecewise) against lensfun over the check grid.
  double rms_px = 0.0;
  double max_px = 0.0;
  int checked = 0;              // check points compared
  int unmapped = 0;             // check points the camera gives no image (not in the figures)
  bool within_tolerance = false;  // max_px ≤ max_error_px
  bool piecewise = false;
  int patches = 0;
  bool tca = false;             // the camera has TCA layers
  double tca_max_px = -1.0;     // the worst channel's max error when tca
  bool vignetting = false;      // the camera carries the vignetting gain
  double aperture = 0.0;
  GainFitSummary vignetting_fit;   // against lensfun's colour modifier, when vignetting
  std::vector<std::string> notes;  // what of the database entry was not applied, and why
  std::string report() const;      // a few lines for the CLI
};

LensCameraSummary lensCamera(const LensDatabase& database, const LensCameraOptions& options);

}  // namespace artcam
