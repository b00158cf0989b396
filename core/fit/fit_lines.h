// SPDX-License-Identifier: Apache-2.0
// Lens calibration from straight lines: the image camera (eq 1, a ratio of quadratics) that maps
// the photo to one in which every traced edge (line_trace.h) is straight, optionally together
// with point pairs. Points are in source pixels (centres at i + 0.5); the camera is stored in
// the normalised frames (frames.h), which also condition the problem (coordinates within ±1).
//
// The objective, in target pixels: for every line, the perpendicular distances of its mapped
// points from their own total-least-squares line (variable projection: the lines are refitted
// at each evaluation, so they are not unknowns); for every pair, its reprojection residual;
// and a gauge. Lines stay lines under any homography, so lines alone leave eight degrees of
// freedom; the gauge fixes them as the least change at the centre: the frame centre maps to
// the target centre, the Jacobian there is the identity and the denominator has no linear term
// (no perspective tilt). A true lens u' = u / (1 - k r²) about the centre already satisfies all
// three, so it is recovered exactly, not up to a homography. With pairs the pairs fix that
// freedom and the gauge only breaks ties (a weight 1e5 times lower).
//
// Models: "radial" (one unknown, u' = u / (1 - k r²) in the normalised frame about the centre)
// and "quadratic" (all 17 tensor entries but the scale, Q_3's last entry held at 1). Auto fits
// the radial lens first, then the quadratic from it, and keeps the quadratic only when all of
// these hold (LinesFitOptions::auto_*): it straightens the traced lines clearly better; it
// straightens HELD-OUT lines clearly better too (each line left out in turn, fitted from the
// others: a quadratic that only bends itself around the traced points fails here); and it keeps
// the picture the radial lens makes, without a keystone or stretch (spacing along the frame's
// rows and columns within auto_max_spacing_change of the radial lens's) and without pulling the
// photo off the frame (line_model_guard.h). Levenberg–Marquardt from the identity never takes a
// step that puts a pole in the source frame (poles.h).
//
// Why auto leans to the radial lens: near a weak lens the quadratic is close to a homography,
// and a few of its 17 directions (a shear u + a·uv keeps every horizontal and vertical edge
// straight) are held only weakly by the lines. On a 6000×4000 façade with 0.2 px clicks the
// radial lens leaves held-out edges within 0.03 px, the quadratic fitted to the same edges
// within about 2 px (tests/core/fit/test_fit_lines.cpp): it needs oblique edges or pairs.
#pragma once

#include "core/fit/options_check.h"
#include "core/model/camera.h"
#include "core/model/fit_record.h"
#include "core/model/line_trace.h"
#include "core/model/status.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class LineModel { Auto, Radial, Quadratic };
std::string_view lineModelName(LineModel model);
std::optional<LineModel> lineModelFromName(std::string_view name);

struct LinesFitOptions {
  LineModel model = LineModel::Auto;
  int max_iterations = 200;
  // Auto keeps the quadratic only when its RMS bow is below this fraction of the radial lens's
  // AND lower by at least auto_min_gain_px: a click's noise alone lets the 17-entry quadratic
  // shave a little off any line set.
  double auto_improvement = 0.75;
  double auto_min_gain_px = 0.05;
  // The guards of auto against a quadratic that keeps the traced lines straight but not the
  // picture: the largest change of the spacing along rows and columns against the radial lens
  // (a keystone of 30 % is 0.3), and the largest fraction of the frame it may leave empty
  // beyond what the radial lens leaves.
  double auto_max_spacing_change = 0.1;
  double auto_max_empty_gain = 0.02;
  // Refuse a camera whose denominator comes closer to zero over the source frame than this
  // fraction of its largest value (the margin of poles.h), as the matches fit does.
  double min_pole_margin = 1e-3;

  // The ranges (options_check.h): model one of the line models, max_iterations 1..100000,
  // auto_improvement in (0, 1], auto_min_gain_px finite and at least 0, auto_max_spacing_change
  // finite and at least 0, auto_max_empty_gain and min_pole_margin from 0 to 1. ok, or a failure
  // naming the first field outside its range; fitLinesCamera returns that failure without fitting.
  Status check(const FieldNames& names = {}) const;
};

// How straight one traced line comes out: its mapped points' perpendicular distances from their
// total-least-squares line, in target pixels.
struct LineBow {
  std::string label;
  int points = 0;
  double max_px = 0.0;  // the remaining bow
  double rms_px = 0.0;
  bool mapped = true;   // false: a point fell on the camera's pole
  // The mapped line's direction (its total-least-squares line), degrees from the target's x
  // axis towards +y, in (-90, 90]: 0 level, 90 plumb.
  double angle_deg = 0.0;
};

// How far a line is tilted from its role's direction, degrees (signed, in (-90, 90]); 0 for a
// line without a role.
double tiltFromRoleDeg(const LineBow& bow, LineRole role);

struct LinesFitSummary {
  Status status;      // not ok: no camera; the message names the cause
  Camera camera;      // valid when status.ok
  LineModel model = LineModel::Radial;
  std::vector<LineBow> bows;         // enabled lines, in input order, after the fit
  std::vector<LineBow> bows_before;  // the same lines through the identity (the photo's bow)
  double rms_bow_px = 0.0;           // over every point of every enabled line
  double max_bow_px = 0.0;
  std::vector<double> pair_residuals_px;  // enabled pairs, in order (empty without pairs)
  double radial_k = 0.0;             // the radial lens's k (normalised frame), when fitted
  int iterations = 0;
  int undetermined = 0;  // directions the data leave free (held by the least-change gauge)
  std::string reason;    // why this model, one line
  FitRecord record() const;  // for the .artcam file: pairs' residuals, reason naming the lines
  std::string report() const;
};

// lines: at least 3 points each (two points are always on a line); pairs in source → target
// pixels (may be empty). Fails, naming the line or the cause, on too few points, a line whose
// points coincide, lines that carry no information about the distortion (all through the frame
// centre, which a radial lens keeps straight) or a fit that would need a pole in the frame.
LinesFitSummary fitLinesCamera(const std::vector<LineTrace>& lines,
                               const std::vector<PointMatch>& pairs, FrameSize source_size,
                               FrameSize target_size, const LinesFitOptions& options = {});

// The bow of each enabled line through a camera (position-only image camera), e.g. for the
// studio to draw or for a held-out check; lines with fewer than 3 points get 0.
std::vector<LineBow> lineBows(const Camera& camera, const std::vector<LineTrace>& lines);

}  // namespace artcam
