// The image effects of issue 6 as named presets with numeric parameters, shared by the studio's
// effects panel and the CLI, and the one render call that applies any of them (layers summed,
// then depth-of-field blur when the camera's depth output is the blur variance).
#pragma once

#include "core/effects/depth_of_field.h"
#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/render/attributed.h"

#include <map>
#include <string>
#include <vector>

namespace artcam {

struct EffectParam {
  std::string name;  // "k", "s-red", …
  double value;      // default
  double min, max;   // for sliders and spin boxes
};

struct EffectSpec {
  std::string name;
  std::string summary;
  std::vector<EffectParam> params;
  bool needs_depth = false;
};

const std::vector<EffectSpec>& effectSpecs();
const EffectSpec* findEffect(const std::string& name);

// What an effect renders with (the .artcam file's camera, layers and depth_output).
struct EffectSetup {
  std::vector<Camera> layers;
  std::string depth_output = "depth";  // or "blur-variance"
};

// Missing parameters take their defaults; throws std::invalid_argument for an unknown effect or
// parameter, or a value the camera refuses (e.g. a pole inside the frame).
EffectSetup buildEffect(const std::string& name, const std::map<std::string, double>& values,
                        FrameSize frame);

// renderLayers, then for "blur-variance" the fast blur stack with σ from the depth output.
// The result's colour is RGBA premultiplied; empty when cancelled (summary->cancelled).
AttributedImage renderEffect(const ImageF& source, const ImageF* depth, const EffectSetup& setup,
                             const AttributedOptions& options = {},
                             AttributedSummary* summary = nullptr);

}  // namespace artcam
