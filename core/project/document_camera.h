// SPDX-License-Identifier: Apache-2.0
// The camera of a studio document, as pure functions of what the document holds, so the
// studio's preview, its export, its saved project and `artcam export` all make the same camera:
//
//   geometry  fitted from the point pairs with the chosen model class (core/fit/fit_image.h),
//             or, when straight lines are traced, from the lines and the pairs together
//             (core/fit/fit_lines.h: the lens that straightens the lines, the pairs fixing the
//             homography the lines leave free), or a camera set by hand;
//   colour    the colour block fitted in the Colour panel, put into the geometry's last stage
//             (core/colour/colour_stage.h, eq 6/7);
//   effects   an ordered stack of effects of the effects table (core/effects/effect_table.h),
//             each composed after what comes before it (composeArtcams, core/model/compose.h):
//             x ↦ effect_n(… effect_1(geometry(x))). Effects that read depth read the depth
//             raster of the painted planes and the depth map (core/depth/depth_raster.h).
//
// Decisions:
// - An effect that cannot be applied (it reads depth and the document has none; composition
//   refuses it) is left out and the summary says which and why: the preview and the export
//   leave it out alike, and the user is told, instead of a render failing or a camera silently
//   being something else.
// - The fit is a pure function of its inputs, which is what makes undo restore it exactly and
//   lets a worker thread fit for the GUI thread with bit-identical results.
#pragma once

#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"
#include "core/model/artcam.h"
#include "core/project/studio_project.h"

#include <optional>
#include <string>
#include <vector>

namespace artcam {

struct DocumentFitInputs {
  FrameSize frame;                  // the photo's pixels; not an image frame: no photo yet
  std::vector<PointMatch> matches;  // every pair, with its enabled flag
  // Straight edges: with one enabled, the geometry is the line fit (with the pairs), with the
  // line model documentLineModel gives.
  std::vector<LineTrace> lines;
  ModelClass model = ModelClass::Auto;
  std::optional<Camera> manual_camera;  // the geometry of a camera set by hand
  std::optional<Camera> colour_block;
  LineModel line_model = LineModel::Auto;  // the model chosen for lines (the studio's model row)
};

// The line fit's model for a document: the one chosen for lines, or, left at auto, the pairs'
// model class saying whether the quadratic is forced (Quadratic; what projects saved before the
// line model existed meant) or chosen by the line fit's auto (any other class: lines cannot
// determine the lower rungs' homography). `artcam fit --lines --model M` is this with M.
LineModel documentLineModel(ModelClass model, LineModel line_model);
// The line fit a document makes: fitLinesCamera with the photo's frame as source and target
// and documentLineModel's model. `artcam fit --lines` on the same lines makes the same camera.
LinesFitSummary fitDocumentLines(const std::vector<LineTrace>& lines,
                                 const std::vector<PointMatch>& pairs, FrameSize frame,
                                 LineModel model);

struct DocumentFit {
  FitSummary fit;
  Camera camera;  // geometry (+ colour block)
  std::vector<double> residual_by_pair;  // target px per pair; negative: unknown
  std::vector<LineBow> line_bows;        // enabled lines' remaining bow, when lines were fitted
};

// Any thread; never throws (an engine exception becomes a failed fit and the identity camera).
DocumentFit fitDocumentGeometry(const DocumentFitInputs& inputs);

// Cameras need image frames; before a photo is open a 1×1 placeholder keeps them valid.
Camera identityImageCamera(FrameSize frame);

// Enabled pairs still missing before `model` is determined (0 when enough).
int pairsNeededFor(ModelClass model, int enabled_pairs);

// The camera the effects apply to: `geometry` (fitDocumentGeometry's camera: the fitted one or
// the hand-set camera's first layer, with the colour block) — or, when the camera set by hand
// has several layers, patches or a blur-variance output, that whole camera with `geometry` as
// its first layer and the colour block put into its other layers too. Patches stay position
// only (their invariant), so a piecewise camera keeps no colour block; `note` says so.
Artcam documentBase(const std::optional<Artcam>& manual, const Camera& geometry,
                    const std::optional<Camera>& colour_block, std::string* note);

struct DocumentArtcam {
  Artcam camera;
  std::vector<int> applied;  // indices of the effects that are in the camera
  std::string note;          // why an effect was left out ("" when all were applied)
};

// The effect stack composed on its own, in order: the costly part (aerial perspective then
// depth of field fits a bridge stage), so the studio makes it once per change of
// the stack or of whether there is depth, not on every refit of the geometry. `camera` is
// empty when no effect could be applied. `has_depth`: the document has depth to read (painted
// planes with their three depths, or a depth map); without it, effects that read depth are
// left out. `frame` is the picture the effects act on (the geometry's target frame).
struct EffectStack {
  std::optional<Artcam> camera;
  std::vector<int> applied;
  std::string note;
};
// `has_second`: the document has a second image, so compositing effects apply.
EffectStack composeEffectStack(const std::vector<EffectStep>& effects, FrameSize frame,
                               bool has_depth, bool has_second = false);

// The whole camera: `base` (the geometry with its colour, or a whole camera set by hand), then
// the composed stack. Composition is associative, so this is the effects applied one by one
// after the geometry; joining base to the composed stack is cheap (microseconds).
DocumentArtcam assembleDocumentArtcam(const Artcam& base, const EffectStack& stack);
// Both steps at once (headless callers that assemble once).
DocumentArtcam assembleDocumentArtcam(const Artcam& base, const std::vector<EffectStep>& effects,
                                      FrameSize frame, bool has_depth, bool has_second = false);

}  // namespace artcam
