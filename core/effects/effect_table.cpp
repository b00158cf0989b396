// SPDX-License-Identifier: Apache-2.0
#include "core/effects/effect_table.h"

#include "core/colour/composite.h"
#include "core/effects/aerial.h"
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "core/effects/image_warps.h"
#include "core/effects/multi_perspective.h"

#include <array>
#include <stdexcept>

namespace artcam {

namespace {

double number(const EffectValues& v, const char* name) { return v.at(name).at(0); }
std::array<double, 3> rgb(const EffectValues& v, const char* r, const char* g, const char* b) {
  return {number(v, r), number(v, g), number(v, b)};
}
Artcam layered(std::vector<Camera> layers) {
  Artcam camera;
  camera.layers = std::move(layers);
  return camera;
}

// The builders: parameters to the camera value.
Artcam radialLens(const EffectValues& v, FrameSize frame) {
  return Artcam(radialLensCamera(number(v, "k"), frame));
}
Artcam lensDistortion(const EffectValues& v, FrameSize frame) {
  LensDistortion lens;
  lens.k1 = number(v, "k1");
  lens.k2 = number(v, "k2");
  const std::vector<double>& c = v.at("centre");
  lens.centre = {c.at(0), c.at(1)};
  lens.scale = number(v, "scale");
  return Artcam(lensDistortionCamera(lens, frame));
}
Artcam twist(const EffectValues& v, FrameSize frame) {
  return Artcam(twistCamera(number(v, "rate"), frame));
}
Artcam inversePerspective(const EffectValues& v, FrameSize frame) {
  return Artcam(inversePerspectiveCamera(number(v, "gain"), frame));
}
Artcam chromaticAberration(const EffectValues& v, FrameSize frame) {
  RgbShiftParams p;
  p.scale = rgb(v, "red", "green", "blue");
  p.dx = rgb(v, "red-dx", "green-dx", "blue-dx");
  p.dy = rgb(v, "red-dy", "green-dy", "blue-dy");
  return layered(rgbShiftLayers(p, frame, frame));
}
Artcam colourShift(const EffectValues& v, FrameSize frame) {
  return layered(colourShiftLayers({rgb(v, "s-red", "s-green", "s-blue")}, frame, frame));
}
Artcam aerialPerspective(const EffectValues& v, FrameSize frame) {
  AerialParams p;
  const std::vector<double>& haze = v.at("haze");
  p.haze = {haze.at(0), haze.at(1), haze.at(2)};
  p.strength = number(v, "strength");
  p.near = number(v, "near");
  p.far = number(v, "far");
  return Artcam(aerialPerspectiveCamera(p, frame, frame));
}
Artcam depthOfField(const EffectValues& v, FrameSize frame) {
  Artcam camera(depthOfFieldCamera(
      {number(v, "focus"), number(v, "blur"), number(v, "thin-lens")}, frame, frame));
  camera.depth_output = DepthOutput::BlurVariance;
  return camera;
}

Artcam composite(const EffectValues& v, FrameSize frame) {
  const auto op = static_cast<CompositeOp>(static_cast<int>(number(v, "op")));
  return Artcam(compositeCamera(op, number(v, "amount"), frame));
}

Eigen::Vector2d xy(const EffectValues& v, const char* name) {
  const std::vector<double>& numbers = v.at(name);
  return {numbers.at(0), numbers.at(1)};
}
Artcam photoPushbroom(const EffectValues& v, FrameSize frame) {
  return Artcam(photoPushbroomCamera({number(v, "reference-depth"), number(v, "angle")}, frame));
}
Artcam photoXSlit(const EffectValues& v, FrameSize frame) {
  return Artcam(photoXSlitCamera(
      {number(v, "slit-u-behind"), number(v, "slit-v-behind"), number(v, "reference-depth")},
      frame));
}
Artcam photoGlc(const EffectValues& v, FrameSize frame) {
  return Artcam(
      photoParallaxCamera({xy(v, "shift"), xy(v, "shift-per-u"), xy(v, "shift-per-v")}, frame));
}

}  // namespace

const std::vector<EffectSpec>& effectSpecs() {
  // "norm": normalised frame units, 1 = half the larger image side (frames.h).
  static const std::vector<EffectSpec> specs = {
      {"barrel", "Barrel", "radial lens u' = u/(1 - k r^2), k < 0 barrel",
       {{"k", "radial coefficient", {-0.15}, -1.0, 0.0, ""}}, false, radialLens},
      {"pincushion", "Pincushion", "radial lens u' = u/(1 - k r^2), k > 0 pincushion",
       {{"k", "radial coefficient", {0.15}, 0.0, 0.45, ""}}, false, radialLens},
      {"lens-distortion", "Lens distortion",
       "a lens's strengths: radial k1 then k2 about a centre, then a scale: "
       "q1 = q/(1 - k1 |q|^2), q2 = q1/(1 - k2 |q1|^2), p' = c + scale·q2, q = p - c",
       {{"k1", "radial strength (< 0 barrel, > 0 pincushion)", {-0.1}, -0.6, 0.45, ""},
        {"k2", "second radial strength, shapes the rim (r^4)", {0.0}, -0.6, 0.45, ""},
        {"centre", "distortion centre (x,y)", {0.0, 0.0}, -0.5, 0.5, "norm"},
        {"scale", "zoom after the distortion", {1.0}, 0.5, 2.0, ""}},
       false, lensDistortion},
      {"twist", "Twist", "each row turns by atan(rate·v): v' = v + rate·u·v",
       {{"rate", "turn per row", {0.3}, -1.0, 1.0, ""}}, false, twist},
      {"inverse-perspective", "Inverse perspective",
       "far (upper) rows magnify: p' = p/(1 + gain·v)",
       {{"gain", "magnification per row", {0.35}, -0.85, 0.85, ""}}, false, inversePerspective},
      {"chromatic-aberration", "Chromatic aberration",
       "three RTcams scale and shift R, G, B (Fig 4 middle)",
       {{"red", "red scale - 1", {0.006}, -0.1, 0.1, ""},
        {"green", "green scale - 1", {0.0}, -0.1, 0.1, ""},
        {"blue", "blue scale - 1", {-0.006}, -0.1, 0.1, ""},
        {"red-dx", "red shift right", {0.0}, -0.1, 0.1, "norm"},
        {"green-dx", "green shift right", {0.0}, -0.1, 0.1, "norm"},
        {"blue-dx", "blue shift right", {0.0}, -0.1, 0.1, "norm"},
        {"red-dy", "red shift down", {0.0}, -0.1, 0.1, "norm"},
        {"green-dy", "green shift down", {0.0}, -0.1, 0.1, "norm"},
        {"blue-dy", "blue shift down", {0.0}, -0.1, 0.1, "norm"}},
       false, chromaticAberration},
      {"colour-shift", "Colour shift",
       "each layer moves by its colour, p(1 + s_k c_k) (Fig 4 right, eq 8/9)",
       {{"s-red", "red layer's s", {0.05}, -0.5, 0.5, ""},
        {"s-green", "green layer's s", {0.0}, -0.5, 0.5, ""},
        {"s-blue", "blue layer's s", {-0.03}, -0.5, 0.5, ""}},
       false, colourShift},
      {"aerial-perspective", "Aerial perspective",
       "contrast falls with log depth towards haze (§3)",
       {{"haze", "linear RGB of the far haze", {0.62, 0.72, 0.86}, 0.0, 1.0, ""},
        {"strength", "haze fraction at far", {0.7}, 0.0, 1.0, ""},
        {"near", "depth where haze starts", {1.0}, 0.01, 1e4, "depth units"},
        {"far", "depth of full strength", {100.0}, 0.02, 1e5, "depth units"}},
       true, aerialPerspective},
      {"depth-of-field", "Depth of field",
       "Gaussian blur, sigma = blur·|d - focus|/(focus + thin-lens·(d - focus)); focus 0 with "
       "thin-lens 0: sigma = blur·d, proportional to depth (§3)",
       {{"focus", "depth in focus (0: blur proportional to depth, with thin-lens 0)", {2.0}, 0.0,
         1e4, "depth units"},
        {"blur", "sigma at infinite depth", {0.01}, 0.0, 0.1, "norm"},
        {"thin-lens", "1 thin lens (/d), 0 linear (/focus)", {1.0}, 0.0, 1.0, ""}},
       true, depthOfField},
      {"composite", "Composite",
       "blends a second image (artcam warp --second) with the photo by a Porter-Duff operator in "
       "premultiplied (projective) alpha, one quadratic form per colour element (eq 6/7)",
       {{"op", "the photo OP the second image (under: the second over the photo; mix with amount "
               "t: (1-t)·photo + t·second)",
         {0.0}, 0.0, static_cast<double>(compositeOpNames().size() - 1), "", compositeOpNames()},
        {"amount", "t: (1-t)·photo + t·(photo OP second)", {1.0}, 0.0, 1.0, ""}},
       false, composite, true},
      // Multi-perspective pictures of the photo and its depth (multi_perspective.h); every
      // parameter is a depth or an image shift, so none needs the photo's focal.
      {"photo-pushbroom", "Push-broom view",
       "push-broom view of the photo and its depth: along the sweep a, a·p' = "
       "(a·p)·d/reference-depth",
       {{"reference-depth", "depth that keeps its size", {3.0}, 0.01, 1e4, "depth units"},
        {"angle", "sweep direction in degrees: 0 along rows, 90 along columns", {0.0}, -90.0,
         90.0, ""}},
       true, photoPushbroom},
      {"photo-xslit", "Crossed-slits view",
       "crossed-slits view of the photo and its depth: u' = u·d·(r + s_u)/(r·(d + s_u)), "
       "r = reference-depth, v' likewise",
       {{"slit-u-behind", "distance of the slit that sets u behind the photo's centre", {0.0}, 0.0,
         100.0, "depth units"},
        {"slit-v-behind", "distance of the slit that sets v behind the photo's centre", {3.0}, 0.0,
         100.0, "depth units"},
        {"reference-depth", "depth that keeps its size", {3.0}, 0.01, 1e4, "depth units"}},
       true, photoXSlit},
      {"photo-glc", "General linear view",
       "GLC view of the photo and its depth, its centre sliding with the image point: "
       "p' = p + e(p')/d",
       {{"shift", "image shift of a point at depth 1, at the centre (x,y)", {0.0, 0.0}, -2.0, 2.0,
         "norm"},
        {"shift-per-u", "change of that shift per unit of u (x,y)", {0.0, 0.3}, -2.0, 2.0, "norm"},
        {"shift-per-v", "change of that shift per unit of v (x,y)", {-0.3, 0.0}, -2.0, 2.0,
         "norm"}},
       true, photoGlc},
  };
  return specs;
}

const EffectSpec* findEffect(const std::string& name) {
  for (const EffectSpec& s : effectSpecs())
    if (s.name == name) return &s;
  return nullptr;
}

const EffectParam* findParam(const EffectSpec& effect, const std::string& name) {
  for (const EffectParam& p : effect.params)
    if (p.name == name) return &p;
  return nullptr;
}

std::string effectLabel(const std::string& name) {
  const EffectSpec* spec = findEffect(name);
  return spec && !spec->label.empty() ? spec->label : name;
}

Artcam buildEffect(const std::string& name, const EffectValues& values, FrameSize frame) {
  const EffectSpec* spec = findEffect(name);
  if (!spec) throw std::invalid_argument("unknown effect \"" + name + "\"");
  return spec->build(completeEffectValues(name, spec->params, values), frame);
}

}  // namespace artcam
