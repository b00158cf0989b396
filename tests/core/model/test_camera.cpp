// SPDX-License-Identifier: Apache-2.0
// The model: eq 3/5 evaluation, RTcam ⊂ ARTcam, eq 8/9, frame changes, chains.
#include "core/model/camera.h"
#include "core/model/frames.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

const Block kPos{BlockKind::Position, 3};
const Block kCol{BlockKind::Colour, 4};

// Independent evaluation of eq 2 by explicit sums, for checking the matrix code.
double quadraticSum(const Eigen::MatrixXd& q, const Eigen::VectorXd& x) {
  double sum = 0.0;
  for (int j = 0; j < x.size(); ++j)
    for (int k = 0; k < x.size(); ++k) sum += q(j, k) * x[j] * x[k];
  return sum;
}

}  // namespace

class TestCamera : public QObject {
  Q_OBJECT

 private slots:
  void identityMapsEveryBlockToItself() {
    const Camera cam = Camera::identity({kPos, kCol}, {640, 480}, {640, 480});
    Eigen::VectorXd x(7);
    x << 0.3, -0.2, 1.0, 0.5 * 0.2, 0.5 * 0.4, 0.5 * 0.9, 0.5;  // premultiplied, alpha 0.5
    const Eigen::VectorXd y = cam.evaluate(x);
    QCOMPARE(y[0], 0.3);
    QCOMPARE(y[1], -0.2);
    QVERIFY(std::abs(y[3] - 0.2) < 1e-15);
    QVERIFY(std::abs(y[4] - 0.4) < 1e-15);
    QVERIFY(std::abs(y[5] - 0.9) < 1e-15);
    QCOMPARE(y[6], 0.5);  // output alpha = d_h, unchanged by the identity
  }

  void evaluationMatchesExplicitSums() {
    const Camera cam = test::randomRationalCamera({100, 80}, {100, 80}, 0.3);
    for (int t = 0; t < 20; ++t) {
      const Eigen::Vector3d x(test::uniform(-1, 1), test::uniform(-1, 1), 1.0);
      const Eigen::VectorXd z = cam.evaluateStage(0, x);
      for (int i = 0; i < 3; ++i)
        QVERIFY(std::abs(z[i] - quadraticSum(cam.stages()[0].q[i], x)) < 1e-14);
      const Eigen::VectorXd y = cam.evaluate(x);
      QVERIFY(std::abs(y[0] - z[0] / z[2]) < 1e-14);  // eq 1
    }
  }

  // The RTcam is the ARTcam with only a position block: adding a colour block whose only
  // terms are colour-identity leaves every position output unchanged.
  void rtcamIsPositionOnlyArtcam() {
    const Camera rt = test::randomRationalCamera({64, 64}, {64, 64}, 0.2);
    Camera art = Camera::identity({kPos, kCol}, {64, 64}, {64, 64});
    for (int i = 0; i < 3; ++i) {
      art.stages()[0].q[i].setZero();
      art.stages()[0].q[i].topLeftCorner(3, 3) = rt.stages()[0].q[i];
    }
    for (int t = 0; t < 20; ++t) {
      const Eigen::Vector3d p(test::uniform(-1, 1), test::uniform(-1, 1), 1.0);
      Eigen::VectorXd x(7);
      x << p, test::uniform(0, 1), test::uniform(0, 1), test::uniform(0, 1), 1.0;
      const Eigen::VectorXd ya = art.evaluate(x);
      const Eigen::VectorXd yr = rt.evaluate(p);
      QVERIFY(std::abs(ya[0] - yr[0]) < 1e-14);
      QVERIFY(std::abs(ya[1] - yr[1]) < 1e-14);
      QVERIFY(std::abs(ya[3] * ya[6] - x[3]) < 1e-14);  // colour passes through
    }
  }

  // Paper eq 8/9: y = (p1, p2)·(s·c1 + c4)/(p3·c4). pc stored symmetric: each coupling term
  // is split between Q_pc and Q_cp, halving it, because x Q xᵀ counts both (eq 10).
  void colourDrivenShiftOfEq8And9() {
    const double s = 0.7;
    Camera cam = Camera::identity({kPos, kCol}, {64, 64}, {64, 64});
    auto& q = cam.stages()[0].q;
    for (int i = 0; i < 3; ++i) q[i].setZero();
    const auto couple = [](Eigen::MatrixXd& m, int r, int c, double v) {
      m(r, c) += 0.5 * v;
      m(c, r) += 0.5 * v;
    };
    couple(q[0], 0, 3, s);    // Q_1pc (1,1) = s
    couple(q[0], 0, 6, 1.0);  // Q_1pc (1,4) = 1
    couple(q[1], 1, 3, s);    // Q_2pc second row
    couple(q[1], 1, 6, 1.0);
    couple(q[2], 2, 6, 1.0);  // p3·c4
    for (int t = 0; t < 20; ++t) {
      const double a = test::uniform(0.2, 1.0), r = test::uniform(0, 1);
      Eigen::VectorXd x(7);
      x << test::uniform(-1, 1), test::uniform(-1, 1), 1.0, a * r, a * 0.3, a * 0.2, a;
      const Eigen::VectorXd y = cam.evaluate(x);
      const double expected_scale = (s * x[3] + x[6]) / (x[2] * x[6]);
      QVERIFY(std::abs(y[0] - x[0] * expected_scale) < 1e-14);
      QVERIFY(std::abs(y[1] - x[1] * expected_scale) < 1e-14);
    }
  }

  // Composing with a homography (the paper's §5, for row vectors): Q_i ← H Q_i Hᵀ equals
  // applying x ← x H, then Q.
  void inputHomographyCompositionEqualsApplyingHThenQ() {
    const Camera cam = test::randomRationalCamera({64, 48}, {64, 48}, 0.2);
    Eigen::Matrix3d h_row = Eigen::Matrix3d::Identity();
    h_row(0, 1) = 0.1;
    h_row(2, 0) = 0.05;
    h_row(0, 2) = 0.03;  // a perspective term
    Camera composed = cam;
    changeInputFrame(composed, 0, h_row);
    for (int t = 0; t < 20; ++t) {
      const Eigen::RowVector3d x(test::uniform(-1, 1), test::uniform(-1, 1), 1.0);
      const Eigen::RowVector3d xh = x * h_row;
      const Eigen::VectorXd direct = cam.evaluate((xh / xh[2]).transpose());
      const Eigen::VectorXd viaComposed = composed.evaluate(x.transpose());
      QVERIFY((direct - viaComposed).norm() < 1e-12);
    }
  }

  void outputFrameChangeMixesTensors() {
    const Camera cam = test::randomRationalCamera({64, 48}, {64, 48}, 0.2);
    Eigen::Matrix3d a;
    a << 2.0, 0.1, 3.0, -0.2, 1.5, -1.0, 0.01, 0.02, 1.0;
    Camera mixed = cam;
    changeOutputFrame(mixed, 0, a);
    for (int t = 0; t < 20; ++t) {
      const Eigen::Vector3d x(test::uniform(-1, 1), test::uniform(-1, 1), 1.0);
      const Eigen::Vector3d z = cam.evaluateHomogeneous(x);
      const Eigen::Vector3d expected = a * z;
      QVERIFY((mixed.evaluateHomogeneous(x) - expected).norm() < 1e-12);
    }
  }

  void pixelFramesRoundTrip() {
    const FrameSize f{600, 400};
    const Eigen::Vector2d p(123.25, 377.5);
    const Eigen::Vector2d n = normalizedFromPixel(f, p);
    QVERIFY(std::abs(n.x() - (123.25 - 300.0) / 300.0) < 1e-15);
    QVERIFY((pixelFromNormalized(f, n) - p).norm() < 1e-12);
    const Eigen::Vector3d ph = pixelFromNormalizedMatrix(f) * Eigen::Vector3d(n.x(), n.y(), 1.0);
    QVERIFY((ph.head<2>() - p).norm() < 1e-12);
  }

  // A camera made on a preview applies unchanged to the full-resolution original.
  void tensorsInPixelsAgreeWithNormalisedEvaluation() {
    const Camera cam = test::randomRationalCamera({600, 400}, {300, 200}, 0.1);
    const std::vector<Eigen::Matrix3d> qp = positionTensorsInPixels(cam);
    for (int t = 0; t < 20; ++t) {
      const Eigen::Vector2d src(test::uniform(0, 600), test::uniform(0, 400));
      const Eigen::Vector3d xp(src.x(), src.y(), 1.0);
      Eigen::Vector3d z;
      for (int i = 0; i < 3; ++i) z[i] = xp.dot(qp[i] * xp);
      const auto expected = targetPixelFromSourcePixel(cam, src);
      QVERIFY(expected.has_value());
      QVERIFY((z.head<2>() / z[2] - *expected).norm() < 1e-9);
    }
  }

  void chainFeedsDividedOutputToNextStage() {
    const Camera a = test::randomRationalCamera({64, 64}, {64, 64}, 0.2);
    const Camera b = test::randomRationalCamera({64, 64}, {64, 64}, 0.2);
    const Camera chain({kPos}, {a.stages()[0], b.stages()[0]}, {64, 64}, {64, 64});
    const Eigen::Vector3d x(0.2, -0.4, 1.0);
    const Eigen::VectorXd ya = a.evaluate(x);
    QVERIFY((chain.evaluate(x) - b.evaluate(ya)).norm() < 1e-13);
  }

  // On the pole circle u² + v² = 0.04 the computed denominator is rounding noise, not 0: the
  // point has no image (it used to map 1e17 px away); a point just off the circle still maps.
  void pointsOnThePoleCurveHaveNoImage() {
    Stage stage;
    stage.q.assign(3, Eigen::MatrixXd::Zero(3, 3));
    stage.q[0](0, 2) = stage.q[0](2, 0) = 0.5;
    stage.q[1](1, 2) = stage.q[1](2, 1) = 0.5;
    stage.q[2] = Eigen::Vector3d(1.0, 1.0, -0.04).asDiagonal();
    const FrameSize frame{64, 48};
    const Camera pole({kPos}, {stage}, frame, frame);
    for (const Eigen::Vector2d& n : {Eigen::Vector2d(0.2, 0.0), Eigen::Vector2d(-0.2, 0.0),
                                     Eigen::Vector2d(0.12, 0.16), Eigen::Vector2d(0.0, 0.2)}) {
      const auto y = targetPixelFromSourcePixel(pole, pixelFromNormalized(frame, n));
      QVERIFY2(!y, qPrintable(QString("(%1, %2) -> (%3, %4)")
                                  .arg(n.x())
                                  .arg(n.y())
                                  .arg(y ? y->x() : 0)
                                  .arg(y ? y->y() : 0)));
    }
    const auto off =
        targetPixelFromSourcePixel(pole, pixelFromNormalized(frame, {0.2 + 1e-6, 0.0}));
    QVERIFY(off && off->allFinite());
    const auto centre = targetPixelFromSourcePixel(pole, pixelFromNormalized(frame, {0.0, 0.0}));
    QVERIFY(centre && (*centre - Eigen::Vector2d(32, 24)).norm() < 1e-9);
  }

  void invalidCamerasAreRefused() {
    Stage bad;
    bad.q.assign(3, Eigen::MatrixXd::Identity(2, 2));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, Camera({kPos}, {bad}, {8, 8}, {8, 8}));
    Stage nan;
    nan.q.assign(3, Eigen::MatrixXd::Identity(3, 3));
    nan.q[1](0, 0) = std::nan("");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, Camera({kPos}, {nan}, {8, 8}, {8, 8}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             Camera::identity({kPos}, {0, 8}, {8, 8}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             Camera::identity({kPos, kPos}, {8, 8}, {8, 8}));
  }
};

QTEST_GUILESS_MAIN(TestCamera)
#include "test_camera.moc"
