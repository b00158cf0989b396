#include "core/effects/effect_presets.h"

#include "core/effects/aerial.h"
#include "core/effects/chromatic.h"
#include "core/effects/image_warps.h"

#include <stdexcept>

namespace artcam {

const std::vector<EffectSpec>& effectSpecs() {
  static const std::vector<EffectSpec> specs = {
      {"barrel", "radial lens u' = u/(1 - k r²), k < 0", {{"k", -0.15, -0.4, 0.0}}, false},
      {"pincushion", "radial lens u' = u/(1 - k r²), k > 0", {{"k", 0.15, 0.0, 0.4}}, false},
      {"twist", "each row turns by atan(rate·v)", {{"rate", 0.3, -1.0, 1.0}}, false},
      {"inverse-perspective", "far (upper) rows magnify, p/(1 + gain·v)", {{"gain", 0.35, -0.8, 0.8}}, false},
      {"chromatic-aberration", "three RTcams scale R, G, B (Fig 4 middle)",
       {{"red", 0.006, -0.05, 0.05}, {"green", 0.0, -0.05, 0.05}, {"blue", -0.006, -0.05, 0.05}}, false},
      {"colour-shift", "each layer moves by its colour, eq 8/9 (Fig 4 right)",
       {{"s-red", 0.05, -0.3, 0.3}, {"s-green", 0.0, -0.3, 0.3}, {"s-blue", -0.03, -0.3, 0.3}}, false},
      {"aerial-perspective", "contrast falls with log depth towards haze (§3)",
       {{"strength", 0.7, 0.0, 1.0}, {"near", 1.0, 0.01, 1e4}, {"far", 100.0, 0.02, 1e5},
        {"haze-r", 0.62, 0.0, 1.0}, {"haze-g", 0.72, 0.0, 1.0}, {"haze-b", 0.86, 0.0, 1.0}}, true},
      {"depth-of-field", "Gaussian blur, σ = blur·|d − focus|/(focus + thin-lens·(d − focus)) (§3)",
       {{"focus", 2.0, 0.01, 1e4}, {"blur", 0.01, 0.0, 0.05}, {"thin-lens", 1.0, 0.0, 1.0}}, true},
  };
  return specs;
}

const EffectSpec* findEffect(const std::string& name) {
  for (const EffectSpec& s : effectSpecs())
    if (s.name == name) return &s;
  return nullptr;
}

EffectSetup buildEffect(const std::string& name, const std::map<std::string, double>& values,
                        FrameSize frame) {
  const EffectSpec* spec = findEffect(name);
  if (!spec) throw std::invalid_argument("unknown effect \"" + name + "\"");
  std::map<std::string, double> v;
  for (const EffectParam& p : spec->params) v[p.name] = p.value;
  for (const auto& [key, value] : values) {
    if (!v.count(key)) throw std::invalid_argument("effect " + name + " has no parameter \"" + key + "\"");
    v[key] = value;
  }
  EffectSetup setup;
  if (name == "barrel" || name == "pincushion") setup.layers = {radialLensCamera(v["k"], frame)};
  else if (name == "twist") setup.layers = {twistCamera(v["rate"], frame)};
  else if (name == "inverse-perspective") setup.layers = {inversePerspectiveCamera(v["gain"], frame)};
  else if (name == "chromatic-aberration") {
    RgbShiftParams p;
    p.scale = {v["red"], v["green"], v["blue"]};
    setup.layers = rgbShiftLayers(p, frame, frame);
  } else if (name == "colour-shift") {
    setup.layers = colourShiftLayers({{v["s-red"], v["s-green"], v["s-blue"]}}, frame, frame);
  } else if (name == "aerial-perspective") {
    AerialParams p;
    p.haze = {v["haze-r"], v["haze-g"], v["haze-b"]};
    p.strength = v["strength"];
    p.near = v["near"];
    p.far = v["far"];
    setup.layers = {aerialPerspectiveCamera(p, frame, frame)};
  } else if (name == "depth-of-field") {
    setup.layers = {depthOfFieldCamera({v["focus"], v["blur"], v["thin-lens"]}, frame, frame)};
    setup.depth_output = "blur-variance";
  }
  return setup;
}

AttributedImage renderEffect(const ImageF& source, const ImageF* depth, const EffectSetup& setup,
                             const AttributedOptions& options, AttributedSummary* summary) {
  AttributedSummary local;
  AttributedSummary& report = summary ? *summary : local;
  AttributedImage out = renderLayers(source, depth, setup.layers, options, &report);
  if (report.cancelled || setup.depth_output != "blur-variance") return out;
  BlurOptions blur;
  blur.threads = options.warp.threads;
  blur.progress = options.warp.progress;
  out.colour = stackBlur(out.colour, sigmaPixelsFromVariance(out.depth), blur);
  if (out.colour.empty()) {
    report.cancelled = true;
    return {};
  }
  return out;
}

}  // namespace artcam
