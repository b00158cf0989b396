// SPDX-License-Identifier: Apache-2.0
// One point's preimage through a camera (core/mapping/point_inverse.h), against inverses known
// in closed form outside the code: a homography's (Eigen's 3×3 inverse), the division model's
// (the root of k r_y r² + r − r_y = 0), and a pole line through the frame, beyond which a
// target's algebraic preimage H⁻¹ t is no preimage by the warp's rule.
#include "core/effects/image_warps.h"
#include "core/mapping/point_inverse.h"
#include "core/model/camera.h"
#include "core/model/frames.h"

#include <Eigen/LU>
#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

const FrameSize kFrame{1200, 800};

// A homography given in pixels (column form) as a camera: Q_i = sym(e₃ h_iᵀ) in the normalised
// frames (eq 1), so x Q_i xᵀ = h_i · x.
Camera homographyCamera(const Eigen::Matrix3d& target_from_source_px) {
  const Eigen::Matrix3d n = pixelFromNormalizedMatrix(kFrame);
  const Eigen::Matrix3d h = n.inverse() * target_from_source_px * n;
  const Eigen::Vector3d e3(0, 0, 1);
  std::vector<Eigen::MatrixXd> q;
  for (int i = 0; i < 3; ++i) q.push_back(symmetricOuter(e3, h.row(i).transpose()));
  return Camera({Block{BlockKind::Position, 3}}, {Stage{{q[0], q[1], q[2]}}}, kFrame, kFrame);
}

Eigen::Vector2d apply(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1.0);
  return q.head<2>() / q.z();
}

}  // namespace

class TestPointInverse : public QObject {
  Q_OBJECT

 private slots:
  void homographyPreimagesAreTheInverseMatrixs() {
    Eigen::Matrix3d h;
    h << 0.9, 0.08, 40.0, -0.05, 1.1, -25.0, 1e-4, -6e-5, 1.0;
    const PointInverse inverse(homographyCamera(h), kFrame, kFrame);
    for (const Eigen::Vector2d& t : {Eigen::Vector2d(600, 400), Eigen::Vector2d(13.25, 771.5),
                                     Eigen::Vector2d(1190, 12), Eigen::Vector2d(-150, 900)}) {
      const std::optional<Eigen::Vector2d> s = inverse.sourceOf(t);
      QVERIFY(s);
      const Eigen::Vector2d truth = apply(h.inverse(), t);
      QVERIFY2(
          (*s - truth).norm() < 1e-6,
          qPrintable(
              QString("%1 %2 vs %3 %4").arg(s->x()).arg(s->y()).arg(truth.x()).arg(truth.y())));
      QVERIFY((*inverse.targetOf(truth) - t).norm() < 1e-9);
    }
  }

  void theDivisionModelTakesItsClosedForm() {
    // y = p / (1 − k |p|²) in the normalised frame (centre 0, half the longer side 1).
    for (double k : {-0.15, 0.2}) {
      const PointInverse inverse(radialLensCamera(k, kFrame), kFrame, kFrame);
      for (const Eigen::Vector2d& t :
           {Eigen::Vector2d(100, 80), Eigen::Vector2d(900, 650), Eigen::Vector2d(640.5, 390.25)}) {
        const Eigen::Vector2d y = normalizedFromPixel(kFrame, t);
        const double ry = y.norm();
        const Eigen::Vector2d p = y * 2.0 / (1.0 + std::sqrt(1.0 + 4.0 * k * ry * ry));
        const Eigen::Vector2d truth = pixelFromNormalized(kFrame, p);
        const std::optional<Eigen::Vector2d> s = inverse.sourceOf(t);
        QVERIFY(s);
        QVERIFY2((*s - truth).norm() < 1e-6, qPrintable(QString("k %1: %2 %3 vs %4 %5")
                                                            .arg(k)
                                                            .arg(s->x())
                                                            .arg(s->y())
                                                            .arg(truth.x())
                                                            .arg(truth.y())));
      }
    }
  }

  void beyondAPoleThereIsNoPreimage() {
    // Denominator 1 − x / 300: the pole line x = 300 crosses the frame; the centre (x = 600) is
    // on its negative side.
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(2, 0) = -1.0 / 300.0;
    const PointInverse inverse(homographyCamera(h), kFrame, kFrame);
    // H⁻¹ (100, 400) = (75, 300): left of the pole, across it from the centre.
    const Eigen::Vector2d beyond = apply(h.inverse(), {100, 400});
    QVERIFY(beyond.x() < 300.0);
    QVERIFY(!inverse.sourceOf({100, 400}));
    // A point on the centre's side maps back to itself through H.
    const Eigen::Vector2d s0(700, 500);
    const std::optional<Eigen::Vector2d> s = inverse.sourceOf(apply(h, s0));
    QVERIFY(s);
    QVERIFY((*s - s0).norm() < 1e-6);
  }
};

QTEST_MAIN(TestPointInverse)
#include "test_point_inverse.moc"
