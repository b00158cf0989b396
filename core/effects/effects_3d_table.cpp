// SPDX-License-Identifier: Apache-2.0
#include "core/effects/effects_3d_table.h"

#include "core/cameras/effects_3d.h"
#include "core/model/frames.h"

#include <cmath>
#include <stdexcept>

namespace artcam {

namespace {

double number(const EffectValues& v, const char* name) { return v.at(name).at(0); }
Eigen::Vector3d vec3(const EffectValues& v, const char* name) {
  const std::vector<double>& x = v.at(name);
  return {x.at(0), x.at(1), x.at(2)};
}

// The builders: parameters (frame units) to the camera.
Camera twist(const EffectValues& v) { return twistEffect({number(v, "rate")}); }
Camera pincushion(const EffectValues& v) {
  return pincushionEffect({number(v, "k"), vec3(v, "centre")});
}
Camera inversePerspective(const EffectValues& v) {
  return inversePerspectiveEffect(
      {vec3(v, "eye"), vec3(v, "at"), vec3(v, "up"), number(v, "gain")});
}
Camera colourScale(const EffectValues& v) {
  return colourScaleEffect({number(v, "strength"), vec3(v, "centre")});
}
Camera chromaticAberration(const EffectValues& v) {
  return chromaticAberrationEffect(
      {number(v, "red"), number(v, "green"), number(v, "blue"), vec3(v, "centre")});
}

EffectParam centreParam(const char* meaning) {
  return {"centre", meaning, {0.0, 0.0, 0.0}, -100.0, 100.0, "radii"};
}

// Moves a camera built in frame units to the world: the effect conjugated by the frame's
// similarity, exact for every quadratic form. The unit frame is left alone, so the numbers of a
// camera built there are the ones typed.
Camera inObjectFrame(Camera camera, const ObjectFrame& frame) {
  if (frame.radius == 1.0 && frame.centre.isZero()) return camera;
  Eigen::Matrix4d to_frame = Eigen::Matrix4d::Identity();  // row form: x_frame = x · to_frame
  to_frame.topLeftCorner<3, 3>() /= frame.radius;
  to_frame.block<1, 3>(3, 0) = -frame.centre.transpose() / frame.radius;
  changeInputFrame(camera, 0, to_frame);
  Eigen::Matrix4d to_world = Eigen::Matrix4d::Identity();  // column form: y = A · y_frame
  to_world.topLeftCorner<3, 3>() *= frame.radius;
  to_world.block<3, 1>(0, 3) = frame.centre;
  changeOutputFrame(camera, 0, to_world);
  return camera;
}

}  // namespace

const std::vector<Effect3dSpec>& effect3dSpecs() {
  // "radii": units of the object frame, 1 = its radius (effects_3d_table.h).
  static const std::vector<Effect3dSpec> specs = {
      {"twist-3d", "Twist",
       "twist about the vertical axis: the section at height Y turns by atan(rate·Y)",
       {{"rate", "tan of the turn one radius above the centre", {0.35}, -10.0, 10.0, ""}}, twist},
      {"pincushion-3d", "Pincushion",
       "P/(1 - k|P - c|^2): points swell outwards, the more the farther out; k < 0 barrel",
       {{"k", "per radius squared: the pole sphere lies 1/sqrt(k) radii out", {0.12}, -10.0, 0.9,
         ""},
        centreParam("centre of the swell")},
       pincushion},
      {"inverse-perspective-3d", "Inverse perspective",
       "objects magnify as they recede from the eye",
       {{"eye", "the viewer (the 3D view: its orbit's eye)", {2.744, 2.058, -3.430}, -1e4, 1e4,
         "radii"},
        {"at", "the point looked at (the 3D view: the cloud's centre)", {0.0, 0.0, 0.0}, -1e4,
         1e4, "radii"},
        {"up", "the viewer's up direction", {0.0, 1.0, 0.0}, -1.0, 1.0, ""},
        {"gain", "magnification per radius of depth; 0: 1/distance(eye, at)", {0.0}, -10.0, 10.0,
         ""}},
       inversePerspective, false, true},
      {"colour-scale", "Colour scale",
       "warm colours expand, cold ones shrink: scale 1 + strength·(r - b) about the centre",
       {{"strength", "scale per unit of red minus blue", {0.35}, -0.95, 0.95, ""},
        centreParam("centre of the scale")},
       colourScale},
      {"chromatic-aberration-3d", "Chromatic aberration",
       "each colour layer scaled by its own 1 + s (render with the colour layers apart)",
       {{"red", "red layer's scale - 1", {0.06}, -0.3, 0.3, ""},
        {"green", "green layer's scale - 1", {0.0}, -0.3, 0.3, ""},
        {"blue", "blue layer's scale - 1", {-0.06}, -0.3, 0.3, ""},
        centreParam("centre of the scales")},
       chromaticAberration, true},
  };
  return specs;
}

const Effect3dSpec* findEffect3d(const std::string& name) {
  for (const Effect3dSpec& s : effect3dSpecs())
    if (s.name == name) return &s;
  return nullptr;
}

Camera buildEffect3d(const std::string& name, const EffectValues& values,
                     const ObjectFrame& frame) {
  const Effect3dSpec* spec = findEffect3d(name);
  if (!spec) throw std::invalid_argument("unknown 3D effect \"" + name + "\"");
  if (!(frame.radius > 0) || !std::isfinite(frame.radius) || !frame.centre.allFinite())
    throw std::invalid_argument(name +
                                ": the object frame needs a finite centre and a positive, "
                                "finite radius");
  return inObjectFrame(spec->build(completeEffectValues(name, spec->params, values)), frame);
}

}  // namespace artcam
