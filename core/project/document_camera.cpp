// SPDX-License-Identifier: Apache-2.0
#include "core/project/document_camera.h"

#include "core/colour/colour_stage.h"
#include "core/model/compose.h"

#include <algorithm>
#include <exception>

namespace artcam {

Camera identityImageCamera(FrameSize f) {
  if (!f.isImage()) f = {1, 1};
  return Camera::identity({Block{BlockKind::Position, 3}}, f, f);
}

int pairsNeededFor(ModelClass model, int enabled_pairs) {
  const ModelClass m = model == ModelClass::Auto ? ModelClass::Translation : model;
  return std::max(0, minimumMatches(m) - enabled_pairs);
}

LineModel documentLineModel(ModelClass model, LineModel line_model) {
  if (line_model != LineModel::Auto) return line_model;
  return model == ModelClass::Quadratic ? LineModel::Quadratic : LineModel::Auto;
}

LinesFitSummary fitDocumentLines(const std::vector<LineTrace>& lines,
                                 const std::vector<PointMatch>& pairs, FrameSize frame,
                                 LineModel model) {
  LinesFitOptions options;
  options.model = model;
  return fitLinesCamera(lines, pairs, frame, frame, options);
}

DocumentFit fitDocumentGeometry(const DocumentFitInputs& in) {
  const FrameSize f = in.frame;
  DocumentFit out;
  out.residual_by_pair.assign(in.matches.size(), -1.0);
  out.camera = identityImageCamera(f);
  if (!f.isImage()) return out;
  try {
    const int enabled = static_cast<int>(std::count_if(
        in.matches.begin(), in.matches.end(), [](const PointMatch& m) { return m.enabled; }));
    const bool has_lines = std::any_of(in.lines.begin(), in.lines.end(),
                                       [](const LineTrace& l) { return l.enabled; });
    if (in.manual_camera) {
      out.camera = *in.manual_camera;
    } else if (has_lines) {
      const LinesFitSummary lines =
          fitDocumentLines(in.lines, in.matches, f, documentLineModel(in.model, in.line_model));
      out.fit.status = lines.status;
      if (lines.status.ok) {
        out.fit.camera = lines.camera;
        out.fit.record = lines.record();
        out.camera = lines.camera;
        out.line_bows = lines.bows;
      }
    } else if (enabled == 0) {
      out.fit.status =
          Status::failure("No point pairs yet: click a source point, then its target.");
    } else if (const int need = pairsNeededFor(in.model, enabled); need > 0) {
      out.fit.status =
          Status::failure("Need " + std::to_string(need) + " more pair" + (need == 1 ? "" : "s") +
                          " for the " + std::string(modelClassName(in.model)) + " model.");
    } else {
      FitOptions options;
      options.model = in.model;
      out.fit = fitImageCamera(in.matches, f, f, options);
      if (out.fit.status.ok) out.camera = out.fit.camera;
    }
    if (!in.matches.empty() && out.camera.blocks().size() == 1) {
      // Residuals of every pair, disabled ones too: they show how far an outlier is off.
      std::vector<PointMatch> all = in.matches;
      for (PointMatch& m : all) m.enabled = true;
      const std::vector<double> r = reprojectionResiduals(out.camera, all);
      for (size_t i = 0; i < r.size() && i < out.residual_by_pair.size(); ++i)
        out.residual_by_pair[i] = r[i];
    }
    // After the residuals: they are a property of the geometry (a position-only camera).
    if (in.colour_block) out.camera = withColourBlock(out.camera, *in.colour_block);
  } catch (const std::exception& e) {
    // A broken contract in the engine must not take the GUI down: report it as a failed fit.
    out.fit = FitSummary{};
    out.fit.status = Status::failure(std::string("Fit failed: ") + e.what());
    out.camera = identityImageCamera(f);
  }
  return out;
}

Artcam documentBase(const std::optional<Artcam>& manual, const Camera& geometry,
                    const std::optional<Camera>& colour_block, std::string* note) {
  const bool whole = manual && (manual->isLayered() || manual->isPiecewise() ||
                                manual->depth_output != DepthOutput::Depth);
  if (!whole) return Artcam(geometry);
  Artcam base = *manual;
  if (base.isPiecewise()) {
    if (colour_block && note)
      *note = "the colour block is not applied to a piecewise camera (its patches are position "
              "only)";
    return base;
  }
  base.layers[0] = geometry;
  if (colour_block)
    for (size_t i = 1; i < base.layers.size(); ++i)
      base.layers[i] = withColourBlock(base.layers[i], *colour_block);
  return base;
}

EffectStack composeEffectStack(const std::vector<EffectStep>& effects, FrameSize frame,
                               bool has_depth, bool has_second) {
  EffectStack out;
  auto leaveOut = [&out](size_t i, const EffectStep& step, const std::string& why) {
    if (!out.note.empty()) out.note += "; ";
    out.note +=
        "effect " + std::to_string(i + 1) + " (" + effectLabel(step.effect) + ") left out: " + why;
  };
  for (size_t i = 0; i < effects.size(); ++i) {
    const EffectStep& step = effects[i];
    const EffectSpec* spec = findEffect(step.effect);
    if (!spec) {
      leaveOut(i, step, "no such effect");
      continue;
    }
    if (spec->needs_depth && !has_depth) {
      leaveOut(i, step, "it reads depth; paint depth planes with their three depths or load a "
                        "depth map");
      continue;
    }
    if (spec->needs_second && !has_second) {
      leaveOut(i, step,
               "it composites a second image and there is none (the studio's File > Second "
               "Image…, a project's \"second\")");
      continue;
    }
    try {
      Artcam effect = buildEffect(step.effect, step.values, frame);
      if (out.camera) {
        Result<Artcam> composed = composeArtcams(*out.camera, effect);
        if (!composed) {
          leaveOut(i, step, composed.status.message);
          continue;
        }
        effect = std::move(*composed.value);
      }
      out.camera = std::move(effect);
      out.applied.push_back(static_cast<int>(i));
    } catch (const std::exception& e) {
      leaveOut(i, step, e.what());
    }
  }
  return out;
}

DocumentArtcam assembleDocumentArtcam(const Artcam& base, const EffectStack& stack) {
  DocumentArtcam out{base, {}, stack.note};
  if (!stack.camera) return out;
  Result<Artcam> composed = composeArtcams(base, *stack.camera);
  if (!composed) {
    out.note += std::string(out.note.empty() ? "" : "; ") +
                "the effects left out: they cannot follow this camera: " + composed.status.message;
    return out;
  }
  out.camera = std::move(*composed.value);
  out.applied = stack.applied;
  return out;
}

DocumentArtcam assembleDocumentArtcam(const Artcam& base, const std::vector<EffectStep>& effects,
                                      FrameSize frame, bool has_depth, bool has_second) {
  // Effects act on the picture the geometry makes: its target frame.
  const FrameSize effect_frame = base.targetSize().isImage() ? base.targetSize() : frame;
  return assembleDocumentArtcam(base,
                                composeEffectStack(effects, effect_frame, has_depth, has_second));
}

}  // namespace artcam
