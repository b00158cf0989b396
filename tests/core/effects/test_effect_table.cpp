// SPDX-License-Identifier: Apache-2.0
// The effects table (effect_table.h): its rows are consistent (defaults inside ranges, known
// units, needs-depth exactly when the camera has a depth block), every parameter reaches the
// camera, values outside a range are refused naming the parameter, and the camera value has
// the shape of each effect (three layers for chromatic aberration and colour shift, the blur
// variance as depth of field's depth output). Closed forms: the radial lens u/(1 − k r²).
#include "core/effects/effect_table.h"

#include <QtTest/QtTest>

#include <cmath>
#include <set>
#include <stdexcept>

using namespace artcam;

namespace {

bool sameCamera(const Camera& a, const Camera& b) {
  if (a.blocks() != b.blocks() || a.sourceSize() != b.sourceSize() ||
      a.targetSize() != b.targetSize() || a.stages().size() != b.stages().size())
    return false;
  for (size_t s = 0; s < a.stages().size(); ++s) {
    if (a.stages()[s].q.size() != b.stages()[s].q.size()) return false;
    for (size_t i = 0; i < a.stages()[s].q.size(); ++i)
      if (a.stages()[s].q[i] != b.stages()[s].q[i]) return false;
  }
  return true;
}

bool sameArtcam(const Artcam& a, const Artcam& b) {
  if (a.layers.size() != b.layers.size() || a.depth_output != b.depth_output) return false;
  for (size_t i = 0; i < a.layers.size(); ++i)
    if (!sameCamera(a.layers[i], b.layers[i])) return false;
  return true;
}

// Halfway from the default to the nearer end of its range (the farther one if it is at an end):
// inside the range, and small enough not to cross a neighbour (aerial's near stays below far).
double otherValue(const EffectParam& p, double d) {
  double end = (p.max - d <= d - p.min) ? p.max : p.min;
  if (end == d) end = (end == p.max) ? p.min : p.max;
  // A named choice's value is an index: the nearest whole one.
  return p.isChoice() ? std::round((d + end) / 2) : (d + end) / 2;
}

}  // namespace

class TestEffectTable : public QObject {
  Q_OBJECT

 private slots:
  void rowsAreConsistent() {
    QVERIFY(effectSpecs().size() >= 8);
    std::set<std::string> names, labels;
    for (const EffectSpec& e : effectSpecs()) {
      QVERIFY2(names.insert(e.name).second, e.name.c_str());
      QVERIFY2(!e.label.empty() && labels.insert(e.label).second, e.name.c_str());  // the studio's
      QVERIFY2(e.build, e.name.c_str());
      QVERIFY2(!e.summary.empty(), e.name.c_str());
      std::set<std::string> params;
      for (const EffectParam& p : e.params) {
        const std::string what = e.name + " " + p.name;
        QVERIFY2(params.insert(p.name).second, what.c_str());
        QVERIFY2(p.size() >= 1 && p.min < p.max && !p.meaning.empty(), what.c_str());
        QVERIFY2(checkEffectValue(p, p.value).empty(), what.c_str());  // default in range
        QVERIFY2(p.unit.empty() || p.unit == "norm" || p.unit == "depth units", what.c_str());
        QVERIFY2(p.name != "size" && p.name != "output", what.c_str());  // the CLI's own options
      }
      // needs_depth exactly when the camera reads a depth block.
      const Artcam camera = buildEffect(e.name, {}, {600, 400});
      QVERIFY2(validateArtcam(camera).ok, e.name.c_str());
      const bool reads_depth = camera.main().layout().find(BlockKind::Depth) >= 0;
      QVERIFY2(reads_depth == e.needs_depth, e.name.c_str());
    }
    for (const char* n : {"barrel", "pincushion", "twist", "inverse-perspective",
                          "chromatic-aberration", "colour-shift", "aerial-perspective", "depth-of-field",
                          "photo-pushbroom", "photo-xslit", "photo-glc"})
      QVERIFY2(names.count(n), n);
  }

  void shapesOfTheCameraValue() {
    const FrameSize frame{320, 240};
    QCOMPARE(buildEffect("chromatic-aberration", {}, frame).layers.size(), size_t{3});
    QCOMPARE(buildEffect("colour-shift", {}, frame).layers.size(), size_t{3});
    QCOMPARE(buildEffect("barrel", {}, frame).layers.size(), size_t{1});
    QVERIFY(buildEffect("depth-of-field", {}, frame).depth_output == DepthOutput::BlurVariance);
    QVERIFY(buildEffect("aerial-perspective", {}, frame).depth_output == DepthOutput::Depth);
    for (const EffectSpec& e : effectSpecs()) {
      const Artcam camera = buildEffect(e.name, {}, frame);
      QVERIFY2(camera.sourceSize() == frame && camera.targetSize() == frame, e.name.c_str());
      QVERIFY2(!camera.isPiecewise(), e.name.c_str());
    }
  }

  // The defaults are used for missing parameters: barrel's k = −0.15 against u/(1 − k r²).
  void radialLensDefaultsAgainstTheClosedForm() {
    for (const auto& [name, k] : {std::pair{"barrel", -0.15}, std::pair{"pincushion", 0.15}}) {
      const Artcam camera = buildEffect(name, {}, {600, 400});
      const double u = 0.4, v = -0.25, g = 1.0 / (1.0 - k * (u * u + v * v));
      Eigen::VectorXd x(3);
      x << u, v, 1;
      const Eigen::VectorXd y = camera.main().evaluate(x);
      QVERIFY(std::abs(y[0] - u * g) < 1e-12 && std::abs(y[1] - v * g) < 1e-12);
    }
  }

  // Every parameter changes the camera: set alone to another value inside its range, the
  // tensors (or layers) differ from the default camera's.
  void everyParameterReachesTheCamera() {
    const FrameSize frame{400, 300};
    for (const EffectSpec& e : effectSpecs()) {
      const Artcam defaults = buildEffect(e.name, {}, frame);
      for (const EffectParam& p : e.params)
        for (int i = 0; i < p.size(); ++i) {
          std::vector<double> value = p.value;
          value[static_cast<size_t>(i)] = otherValue(p, value[static_cast<size_t>(i)]);
          const Artcam changed = buildEffect(e.name, {{p.name, value}}, frame);
          const std::string what = e.name + " " + p.name + "[" + std::to_string(i) + "]";
          QVERIFY2(!sameArtcam(changed, defaults), what.c_str());
        }
    }
  }

  void valuesOutsideARangeAreRefused() {
    const EffectSpec* barrel = findEffect("barrel");
    QVERIFY(barrel);
    const EffectParam* k = findParam(*barrel, "k");
    QVERIFY(k);
    QCOMPARE(QString::fromStdString(rangeText(*k)), QString::fromUtf8("-1 … 0"));
    QVERIFY(checkEffectValue(*k, {-1.0}).empty());
    QVERIFY(checkEffectValue(*k, {0.0}).empty());
    QCOMPARE(QString::fromStdString(checkEffectValue(*k, {0.9})),
             QString::fromUtf8("k = 0.9 is outside its range -1 … 0"));
    QVERIFY(!checkEffectValue(*k, {std::nan("")}).empty());
    QCOMPARE(QString::fromStdString(checkEffectValue(*k, {-0.1, -0.1})), QString("k expects one number"));
    const EffectParam* haze = findParam(*findEffect("aerial-perspective"), "haze");
    QVERIFY(haze);
    QCOMPARE(haze->size(), 3);
    QCOMPARE(QString::fromStdString(defaultText(*haze)), QString("0.62,0.72,0.86"));
    QCOMPARE(QString::fromStdString(checkEffectValue(*haze, {0.5})),
             QString("haze expects 3 comma-separated numbers"));
    const EffectParam* near = findParam(*findEffect("aerial-perspective"), "near");
    QCOMPARE(QString::fromStdString(rangeText(*near)), QString::fromUtf8("0.01 … 10000 depth units"));

    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, buildEffect("barrel", {{"k", {0.9}}}, {600, 400}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, buildEffect("barrel", {{"rate", {0.1}}}, {600, 400}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, buildEffect("no-such", {}, {600, 400}));
    // Inside the ranges, a camera may still refuse a combination: near must stay below far.
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect("aerial-perspective", {{"near", {50.0}}, {"far", {10.0}}}, {600, 400}));
  }

  // The ranges of the pole-limited lenses hold on every frame shape (the header's bound): the
  // range ends build on landscape, portrait and square frames, and just past the end the camera
  // itself refuses the square frame (its pole reaches the corner).
  void poleLimitedRangesHoldOnEveryFrame() {
    for (const FrameSize frame : {FrameSize{600, 400}, FrameSize{400, 600}, FrameSize{300, 300}}) {
      for (const double k : {-1.0, 0.45})
        buildEffect(k < 0 ? "barrel" : "pincushion", {{"k", {k}}}, frame);
      for (const double gain : {-0.85, 0.85}) buildEffect("inverse-perspective", {{"gain", {gain}}}, frame);
    }
    const EffectSpec* pincushion = findEffect("pincushion");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, pincushion->build({{"k", {0.48}}}, {300, 300}));
    const EffectSpec* inverse = findEffect("inverse-perspective");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, inverse->build({{"gain", {0.91}}}, {400, 600}));
  }
};

QTEST_GUILESS_MAIN(TestEffectTable)
#include "test_effect_table.moc"
