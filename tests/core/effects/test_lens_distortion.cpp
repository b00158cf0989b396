// SPDX-License-Identifier: Apache-2.0
// The lens-distortion row of the effects table against its closed form, computed here point by
// point: q = p − c, q₁ = q/(1 − k1|q|²), q₂ = q₁/(1 − k2|q₁|²), p' = c + s·q₂; with k2 = 0,
// centre 0 and scale 1 it is the barrel preset's radial lens; poles inside what a stage is fed
// are refused.
#include "core/effects/effect_table.h"
#include "core/effects/image_warps.h"

#include <QtTest/QtTest>

#include <stdexcept>

using namespace artcam;

namespace {

Eigen::Vector2d closedForm(const Eigen::Vector2d& p, double k1, double k2, const Eigen::Vector2d& c,
                           double s) {
  const Eigen::Vector2d q = p - c;
  const Eigen::Vector2d q1 = q / (1.0 - k1 * q.squaredNorm());
  const Eigen::Vector2d q2 = q1 / (1.0 - k2 * q1.squaredNorm());
  return c + s * q2;
}

}  // namespace

class TestLensDistortion : public QObject {
  Q_OBJECT

 private slots:
  void matchesItsClosedForm() {
    const FrameSize frame{600, 400};
    const Eigen::Vector2d c(0.1, -0.05);
    const Artcam cam = buildEffect(
        "lens-distortion",
        {{"k1", {-0.2}}, {"k2", {0.1}}, {"centre", {0.1, -0.05}}, {"scale", {1.1}}}, frame);
    QCOMPARE(cam.main().stages().size(), size_t{2});
    for (double x : {-1.0, -0.4, 0.0, 0.3, 1.0})
      for (double y : {-0.66, -0.2, 0.0, 0.5, 0.66}) {
        const auto got = targetFromSourceNormalized(cam.main(), {x, y});
        QVERIFY(got.has_value());
        const Eigen::Vector2d want = closedForm({x, y}, -0.2, 0.1, c, 1.1);
        QVERIFY2((*got - want).norm() < 1e-12, qPrintable(QString("(%1, %2): %3 %4 against %5 %6")
                                                              .arg(x)
                                                              .arg(y)
                                                              .arg(got->x())
                                                              .arg(got->y())
                                                              .arg(want.x())
                                                              .arg(want.y())));
      }
  }

  void oneStageIsTheRadialLens() {
    const FrameSize frame{600, 400};
    const Artcam lens = buildEffect("lens-distortion", {{"k1", {-0.15}}}, frame);
    QCOMPARE(lens.main().stages().size(), size_t{1});
    const Artcam barrel = buildEffect("barrel", {{"k", {-0.15}}}, frame);
    for (double x : {-1.0, 0.2, 0.9})
      for (double y : {-0.6, 0.1}) {
        const auto a = targetFromSourceNormalized(lens.main(), {x, y});
        const auto b = targetFromSourceNormalized(barrel.main(), {x, y});
        QVERIFY(a && b);
        QVERIFY((*a - *b).norm() < 1e-12);
      }
  }

  void polesInsideAreRefused() {
    const FrameSize frame{600, 400};
    // Corner r² = 1 + (2/3)² ≈ 1.444: k1 0.45 gives 0.65 < 0.95 (taken), but off-centre the far
    // corner is at r² = 1.5² + (2/3 + 0.5)² ≈ 3.61, so k1 0.3 gives 1.08 (refused).
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             lensDistortionCamera({0.3, 0.0, {-0.5, -0.5}, 1.0}, frame));
    (void)lensDistortionCamera({0.3, 0.0, {0.0, 0.0}, 1.0}, frame);
    // The first stage takes the corner to r₁ = 1.2019/(1 − 0.45·1.444) ≈ 3.42, so k2 0.1 puts
    // the second pole (k2·r₁² ≈ 1.17) inside its input.
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             lensDistortionCamera({0.45, 0.1, {0.0, 0.0}, 1.0}, frame));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             lensDistortionCamera({0.0, 0.0, {0.0, 0.0}, 0.0}, frame));
  }
};

QTEST_GUILESS_MAIN(TestLensDistortion)
#include "test_lens_distortion.moc"
