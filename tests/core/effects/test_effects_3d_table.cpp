// SPDX-License-Identifier: Apache-2.0
// The 3D effects table (effects_3d_table.h): its rows are consistent (defaults inside ranges,
// names apart from the image table's, a human name each); in the unit object frame a row's
// camera is exactly the effects_3d.h call with the defaults `artcam preset` always used; in any
// other frame it is that camera moved by the frame's rule, world = centre + radius · frame,
// point by point; values outside a range and frames without a positive radius are refused.
#include "core/cameras/effects_3d.h"
#include "core/effects/effect_table.h"
#include "core/effects/effects_3d_table.h"
#include "core/model/artcam.h"

#include <QtTest/QtTest>

#include <cmath>
#include <set>
#include <stdexcept>

using namespace artcam;

namespace {

bool sameCamera(const Camera& a, const Camera& b) {
  if (a.blocks() != b.blocks() || a.stages().size() != b.stages().size()) return false;
  for (size_t s = 0; s < a.stages().size(); ++s) {
    if (a.stages()[s].q.size() != b.stages()[s].q.size()) return false;
    for (size_t i = 0; i < a.stages()[s].q.size(); ++i)
      if (a.stages()[s].q[i] != b.stages()[s].q[i]) return false;
  }
  return true;
}

// A point (and, when the camera reads colour, an orange colour at alpha 0.8) through `camera`:
// the moved position.
Eigen::Vector3d moved(const Camera& camera, const Eigen::Vector3d& p) {
  Eigen::VectorXd x(camera.dimension());
  x.head<4>() << p, 1.0;
  if (camera.dimension() == 8) x.tail<4>() << 0.9 * 0.8, 0.5 * 0.8, 0.1 * 0.8, 0.8;
  return camera.evaluate(x).head<3>();
}

}  // namespace

class TestEffects3dTable : public QObject {
  Q_OBJECT

 private slots:
  void rowsAreConsistent() {
    std::set<std::string> names, labels;
    for (const Effect3dSpec& e : effect3dSpecs()) {
      QVERIFY2(names.insert(e.name).second, e.name.c_str());
      QVERIFY2(!findEffect(e.name), e.name.c_str());  // one `artcam preset NAME` each
      QVERIFY2(!e.label.empty() && labels.insert(e.label).second, e.name.c_str());
      QVERIFY2(!e.summary.empty() && e.build, e.name.c_str());
      std::set<std::string> params;
      for (const EffectParam& p : e.params) {
        const std::string what = e.name + " " + p.name;
        QVERIFY2(params.insert(p.name).second, what.c_str());
        QVERIFY2(p.size() >= 1 && p.min < p.max && !p.meaning.empty(), what.c_str());
        QVERIFY2(checkEffectValue(p, p.value).empty(), what.c_str());
        QVERIFY2(p.unit.empty() || p.unit == "radii", what.c_str());
        // The CLI's own options of a 3D preset.
        QVERIFY2(p.name != "object-centre" && p.name != "object-radius" && p.name != "output",
                 what.c_str());
      }
      QVERIFY2(!e.viewer || (params.count("eye") && params.count("at")), e.name.c_str());
      QVERIFY2(validateArtcam(Artcam(buildEffect3d(e.name, {}))).ok, e.name.c_str());
    }
    for (const char* n : {"twist-3d", "pincushion-3d", "inverse-perspective-3d", "colour-scale",
                          "chromatic-aberration-3d"})
      QVERIFY2(names.count(n), n);
    QVERIFY(findEffect3d("chromatic-aberration-3d")->colour_layers);
    QVERIFY(findEffect3d("inverse-perspective-3d")->viewer);
  }

  // In the unit frame the numbers are object units: exactly the cameras of effects_3d.h with
  // the defaults `artcam preset` wrote before there was a table.
  void unitFrameIsTheDirectCall() {
    QVERIFY(sameCamera(buildEffect3d("twist-3d", {}), twistEffect({0.35})));
    QVERIFY(sameCamera(buildEffect3d("pincushion-3d", {}), pincushionEffect({0.12, {0, 0, 0}})));
    QVERIFY(sameCamera(buildEffect3d("inverse-perspective-3d", {}),
                       inversePerspectiveEffect({{2.744, 2.058, -3.430}, {0, 0, 0}, {0, 1, 0}, 0})));
    QVERIFY(sameCamera(buildEffect3d("colour-scale", {}), colourScaleEffect({0.35, {0, 0, 0}})));
    QVERIFY(sameCamera(buildEffect3d("chromatic-aberration-3d", {}),
                       chromaticAberrationEffect({0.06, 0.0, -0.06, {0, 0, 0}})));
    QVERIFY(sameCamera(buildEffect3d("pincushion-3d", {{"k", {-0.5}}, {"centre", {1, 2, 3}}}),
                       pincushionEffect({-0.5, {1, 2, 3}})));
  }

  // The frame's rule, for every row and parameter set: the camera in frame (c, r) moves a world
  // point P to c + r · E((P − c)/r), E the row's camera in the unit frame.
  void otherFramesMoveTheUnitCamera() {
    const ObjectFrame frame{{3.0, -1.5, 10.0}, 40.0};
    for (const Effect3dSpec& e : effect3dSpecs()) {
      const Camera unit = buildEffect3d(e.name, {});
      const Camera world = buildEffect3d(e.name, {}, frame);
      for (const Eigen::Vector3d& local : {Eigen::Vector3d(0.3, -0.4, 0.5),
                                           Eigen::Vector3d(-0.7, 0.2, -0.1),
                                           Eigen::Vector3d(0.05, 0.9, 0.3)}) {
        const Eigen::Vector3d p = frame.centre + frame.radius * local;
        const Eigen::Vector3d want = frame.centre + frame.radius * moved(unit, local);
        const Eigen::Vector3d got = moved(world, p);
        QVERIFY2((got - want).norm() <= 1e-9 * (1 + want.norm()), e.name.c_str());
      }
    }
    // So a default suits a cloud of any size: the pincushion's pole sphere (1/√0.12 radii) stays
    // outside the frame's sphere of radius 40, whose points move outwards.
    const Camera swell = buildEffect3d("pincushion-3d", {}, frame);
    const Eigen::Vector3d rim = frame.centre + Eigen::Vector3d(frame.radius, 0, 0);
    QVERIFY((moved(swell, rim) - frame.centre).norm() > frame.radius);
  }

  void refusals() {
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, buildEffect3d("twist", {}));  // the image one
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect3d("pincushion-3d", {{"k", {0.95}}}));  // range
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect3d("colour-scale", {{"centre", {0, 0}}}));  // size
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect3d("twist-3d", {{"gain", {0.1}}}));  // no such parameter
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, buildEffect3d("twist-3d", {}, {{0, 0, 0}, 0}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect3d("twist-3d", {}, {{0, 0, 0}, std::nan("")}));
    // The camera's own refusal: an eye on its target.
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect3d("inverse-perspective-3d", {{"eye", {0, 0, 0}}}));
    try {
      buildEffect3d("pincushion-3d", {{"k", {0.95}}});
    } catch (const std::invalid_argument& e) {
      QCOMPARE(QString::fromUtf8(e.what()),
               QString::fromUtf8("pincushion-3d: k = 0.95 is outside its range -10 … 0.9"));
    }
  }
};

QTEST_APPLESS_MAIN(TestEffects3dTable)
#include "test_effects_3d_table.moc"
