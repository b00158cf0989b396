// SPDX-License-Identifier: Apache-2.0
// The Fig 1 effects as tensors, point by point against their closed forms (effects_3d.h).
#include "core/cameras/effects_3d.h"
#include "core/cameras/projective_cameras.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

Eigen::Vector3d randomPoint(double r = 1.0) {
  return {test::uniform(-r, r), test::uniform(-r, r), test::uniform(-r, r)};
}

Eigen::Vector3d movePoint(const Camera& cam, const Eigen::Vector3d& p) {
  return cam.evaluate(Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0)).head<3>();
}

// Position and colour through a position+colour camera; colour given unpremultiplied.
std::pair<Eigen::Vector3d, Eigen::Vector4d> moveColoured(const Camera& cam,
                                                         const Eigen::Vector3d& p,
                                                         const Eigen::Vector3d& rgb, double a) {
  Eigen::VectorXd x(8);
  x << p, 1.0, rgb * a, a;
  const Eigen::VectorXd y = cam.evaluate(x);
  return {y.head<3>(), y.tail<4>()};
}

bool near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-12) {
  return (a - b).norm() <= tol * (1 + b.norm());
}

}  // namespace

class TestEffects : public QObject {
  Q_OBJECT

 private slots:
  void twistTurnsEachHeightByAtanOfRateTimesHeight() {
    const double rate = 0.4;
    const Camera cam = twistEffect({rate});
    for (int t = 0; t < 100; ++t) {
      const Eigen::Vector3d p = randomPoint();
      const double angle = std::atan(rate * p.y()),
                   grow = std::sqrt(1 + rate * rate * p.y() * p.y());
      const Eigen::Vector3d expected(grow * (std::cos(angle) * p.x() - std::sin(angle) * p.z()),
                                     p.y(),
                                     grow * (std::sin(angle) * p.x() + std::cos(angle) * p.z()));
      QVERIFY(near(movePoint(cam, p), expected));
    }
  }

  void pincushionSwellsRadiallyAboutItsCentre() {
    PincushionParams pp;
    pp.k = 0.1;
    pp.centre = {0.3, -0.2, 0.1};
    const Camera cam = pincushionEffect(pp);
    for (int t = 0; t < 100; ++t) {
      const Eigen::Vector3d p = randomPoint();
      const Eigen::Vector3d d = p - pp.centre;
      QVERIFY(near(movePoint(cam, p), pp.centre + d / (1 - 0.1 * d.squaredNorm())));
    }
  }

  void inversePerspectiveMakesApparentSizeGrowWithDepth() {
    InversePerspectiveParams ip;
    ip.eye = {1, 2, -6};
    ip.target = {0.2, 0, 0.1};
    ip.gain = 0.15;
    const Camera cam = inversePerspectiveEffect(ip);
    const CameraPose view = CameraPose::lookAt(ip.eye, ip.target);
    const double e = (ip.target - ip.eye).norm();
    PinholeParams pin;
    pin.pose = view;
    const Camera viewer = pinholeCamera(pin);
    for (int t = 0; t < 100; ++t) {
      const Eigen::Vector3d p = ip.target + randomPoint(2);
      const Eigen::Vector3d c = view.cameraFromWorld(p);
      const Eigen::Vector3d moved = view.cameraFromWorld(movePoint(cam, p));
      const double depth = c.z() - e;
      QVERIFY(std::abs(moved.z() - c.z()) < 1e-12 * (1 + c.z()));  // depth kept
      // Seen by the viewer, the lateral offset appears at (X/Z_eye_target)·m(t), m = 1/(1 - g t).
      const Eigen::Vector2d seen =
          (viewer
               .evaluate(Eigen::Vector4d(movePoint(cam, p).x(), movePoint(cam, p).y(),
                                         movePoint(cam, p).z(), 1))
               .head<2>());
      const Eigen::Vector2d expected = 2.0 * c.head<2>() / e / (1 - 0.15 * depth);
      QVERIFY2((seen - expected).norm() < 1e-10 * (1 + expected.norm()),
               qPrintable(QString::number((seen - expected).norm())));
    }
  }

  void colourScaleExpandsWarmAndShrinksColdKeepingColour() {
    ColourScaleParams cs;
    cs.strength = 0.3;
    const Camera cam = colourScaleEffect(cs);
    const Eigen::Vector3d p(0.5, -0.25, 1.0);
    const auto [warm, warm_c] = moveColoured(cam, p, {1, 0.2, 0}, 0.5);
    const auto [cold, cold_c] = moveColoured(cam, p, {0, 0.2, 1}, 1.0);
    const auto [grey, grey_c] = moveColoured(cam, p, {0.4, 0.4, 0.4}, 1.0);
    QVERIFY(near(warm, p * 1.3));
    QVERIFY(near(cold, p * 0.7));
    QVERIFY(near(grey, p));
    // Colour unchanged: eq 5 divides by alpha (unpremultiplied out), alpha kept.
    QVERIFY((warm_c - Eigen::Vector4d(1, 0.2, 0, 0.5)).norm() < 1e-12);
    QVERIFY((cold_c - Eigen::Vector4d(0, 0.2, 1, 1)).norm() < 1e-12);
  }

  void chromaticAberrationScalesEachLayerByItsOwnFactor() {
    ChromaticAberrationParams ca;
    ca.red = 0.1;
    ca.green = 0.02;
    ca.blue = -0.1;
    ca.centre = {0.1, 0.1, 0.1};
    const Camera cam = chromaticAberrationEffect(ca);
    const Eigen::Vector3d p(0.7, 0.3, -0.4);
    const Eigen::Vector3d d = p - ca.centre;
    QVERIFY(near(moveColoured(cam, p, {1, 0, 0}, 1).first, ca.centre + 1.1 * d));
    QVERIFY(near(moveColoured(cam, p, {0, 1, 0}, 1).first, ca.centre + 1.02 * d));
    QVERIFY(near(moveColoured(cam, p, {0, 0, 0.5}, 1).first, ca.centre + 0.95 * d));
  }

  void effectsAreSingleStagesThatValidate() {
    for (const Camera& c : {twistEffect({}), pincushionEffect({}), inversePerspectiveEffect({}),
                            colourScaleEffect({}), chromaticAberrationEffect({})}) {
      c.validate();
      QCOMPARE(c.stages().size(), size_t(1));
    }
  }
};

QTEST_GUILESS_MAIN(TestEffects)
#include "test_effects.moc"
