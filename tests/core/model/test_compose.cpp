// SPDX-License-Identifier: Apache-2.0
// Composition: compose(first, second) must map every pixel where second(first(·)) does,
// evaluated independently through the two cameras one after the other.
#include "core/model/compose.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::test;

namespace {

// Largest pixel distance between composed(p) and second(first(p)) over a grid of first's
// source pixels; points where either side has no image are counted and must agree.
double maxSequentialError(const Camera& composed, const Camera& first, const Camera& second) {
  double worst = 0.0;
  const FrameSize s = first.sourceSize();
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      const Eigen::Vector2d p(s.width * (0.02 + 0.96 * i / 8.0), s.height * (0.02 + 0.96 * j / 8.0));
      const auto mid = targetPixelFromSourcePixel(first, p);
      const auto expected = mid ? targetPixelFromSourcePixel(second, *mid) : std::nullopt;
      const auto got = targetPixelFromSourcePixel(composed, p);
      if (expected.has_value() != got.has_value()) return std::numeric_limits<double>::infinity();
      if (got) worst = std::max(worst, (*got - *expected).norm());
    }
  return worst;
}

Camera withColour(const Camera& position_camera, double colour_gain_u) {
  // Position block from `position_camera`; colour scaled by (w + g·u) so colour depends on
  // position (a pc coupling in the colour outputs).
  const std::vector<Block> blocks{{BlockKind::Position, 3}, {BlockKind::Colour, 4}};
  Stage stage;
  for (int i = 0; i < 3; ++i) {
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(7, 7);
    q.topLeftCorner(3, 3) = position_camera.stages()[0].q[static_cast<size_t>(i)];
    stage.q.push_back(q);
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Zero(7);
  scale[2] = 1.0;
  scale[0] = colour_gain_u;
  for (int j = 0; j < 4; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(7);
    e[3 + j] = 1.0;
    stage.q.push_back(symmetricOuter(e, scale));
  }
  return Camera(blocks, {stage}, position_camera.sourceSize(), position_camera.targetSize());
}

}  // namespace

class TestCompose : public QObject {
  Q_OBJECT

 private slots:
  void rationalThenHomographyIsOneStage() {
    const Camera first = randomRationalCamera({640, 480}, {640, 480});
    const Camera second = randomHomographyCamera({640, 480}, {800, 600});
    CompositionSummary summary;
    const auto c = composeCameras(first, second, &summary);
    QVERIFY2(c.ok(), c.status.message.c_str());
    QCOMPARE(summary.kind, CompositionKind::OutputHomography);
    QCOMPARE(c->stages().size(), size_t{1});
    QCOMPARE(c->targetSize(), (FrameSize{800, 600}));
    QVERIFY(maxSequentialError(*c, first, second) < 1e-9);
  }

  void homographyThenRationalIsOneStage() {
    const Camera first = randomHomographyCamera({1000, 700}, {640, 480});
    const Camera second = randomRationalCamera({640, 480}, {640, 480});
    CompositionSummary summary;
    const auto c = composeCameras(first, second, &summary);
    QVERIFY2(c.ok(), c.status.message.c_str());
    QCOMPARE(summary.kind, CompositionKind::InputHomography);
    QCOMPARE(c->stages().size(), size_t{1});
    QVERIFY(maxSequentialError(*c, first, second) < 1e-9);
  }

  void framesOfOneShapeMeetAsWarpWouldAndSaySo() {
    // first's target (320×240) is not second's source (640×480) but has its shape: second
    // applies as warp would apply it to first's 320×240 output (its frames scaled by ½ per
    // axis), so the target frame is 250×250, not second's 500×500, and the summary says so.
    const Camera first = randomRationalCamera({320, 240}, {320, 240});
    const Camera second = randomRationalCamera({640, 480}, {500, 500});
    const Eigen::Vector2d half(0.5, 0.5);
    const auto inTurn = [&](const Camera& a, const Eigen::Vector2d& p) -> std::optional<Eigen::Vector2d> {
      const auto mid = targetPixelFromSourcePixel(a, p);
      if (!mid) return std::nullopt;
      const auto out = targetPixelFromSourcePixel(second, mid->cwiseQuotient(half));
      if (!out) return std::nullopt;
      return out->cwiseProduct(half);
    };
    for (const Camera& a : {first, randomHomographyCamera({320, 240}, {320, 240})}) {
      CompositionSummary summary;
      const auto c = composeCameras(a, second, &summary);
      QVERIFY2(c.ok(), c.status.message.c_str());
      QCOMPARE(c->targetSize(), (FrameSize{250, 250}));
      QVERIFY2(summary.description.find("made for 640x480") != std::string::npos &&
                   summary.description.find("320x240") != std::string::npos,
               summary.description.c_str());
      double worst = 0.0;
      for (int k = 0; k < 100; ++k) {
        const Eigen::Vector2d p(uniform(10, 310), uniform(10, 230));
        const auto expected = inTurn(a, p);
        const auto got = targetPixelFromSourcePixel(*c, p);
        QCOMPARE(got.has_value(), expected.has_value());
        if (got) worst = std::max(worst, (*got - *expected).norm());
      }
      QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
    }
  }

  void framesOfAnotherShapeAreRefused() {
    // The measured surprise: a camera made for 256×171 after one whose target is 320×320 gave
    // a 171×256-ish picture of a corner of it. Refused, naming both frames.
    const Camera first = randomHomographyCamera({320, 320}, {320, 320});
    const Camera second = randomRationalCamera({256, 171}, {256, 171});
    const auto c = composeCameras(first, second);
    QVERIFY(!c.ok());
    QVERIFY2(c.status.message.find("320x320") != std::string::npos &&
                 c.status.message.find("256x171") != std::string::npos &&
                 c.status.message.find("shape") != std::string::npos,
             c.status.message.c_str());
  }

  void twoHomographiesStayAHomography() {
    const Camera a = randomHomographyCamera({640, 480}, {640, 480});
    const Camera b = randomHomographyCamera({640, 480}, {640, 480});
    const auto c = composeCameras(a, b);
    QVERIFY(c.ok());
    QCOMPARE(c->stages().size(), size_t{1});
    QVERIFY(analyseStructure(*c).geometry <= GeometryClass::Homography);
    QVERIFY(maxSequentialError(*c, a, b) < 1e-9);
  }

  void twoRationalCamerasChain() {
    const Camera a = randomRationalCamera({640, 480}, {640, 480});
    const Camera b = randomRationalCamera({640, 480}, {640, 480}, 0.08);
    CompositionSummary summary;
    const auto c = composeCameras(a, b, &summary);
    QVERIFY(c.ok());
    QCOMPARE(summary.kind, CompositionKind::Chain);
    QCOMPARE(c->stages().size(), size_t{2});
    QVERIFY(maxSequentialError(*c, a, b) < 1e-9);
  }

  void attributedCamerasChainAndKeepColour() {
    // A projective homography on position+colour cameras must not be folded: its change of
    // homogeneous weight would not cancel in the colour outputs' (w + g·u) factor.
    const Camera first = withColour(randomHomographyCamera({640, 480}, {640, 480}), 0.0);
    const Camera second = withColour(randomRationalCamera({640, 480}, {640, 480}), 0.2);
    const auto c = composeCameras(first, second);
    QVERIFY2(c.ok(), c.status.message.c_str());
    double worst = 0.0;
    for (int k = 0; k < 50; ++k) {
      Eigen::VectorXd x(7);
      const double a = uniform(0.2, 0.9);
      x << uniform(-0.9, 0.9), uniform(-0.7, 0.7), 1.0, a * uniform(0, 1), a * uniform(0, 1),
          a * uniform(0, 1), a;
      const Eigen::VectorXd expected =
          second.evaluate(first.rehomogenise(first.evaluateHomogeneous(x)));
      worst = std::max(worst, (c->evaluate(x) - expected).cwiseAbs().maxCoeff());
    }
    QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
  }

  void refusesMismatchedCameras() {
    const Camera image = randomRationalCamera({640, 480}, {640, 480});
    const Camera coloured = withColour(image, 0.1);
    const auto c = composeCameras(image, coloured);
    QVERIFY(!c.ok());
    QVERIFY(c.status.message.find("different blocks") != std::string::npos);
    Camera object_space = image;
    object_space.setFrames({0, 0}, {0, 0});
    const auto d = composeCameras(image, object_space);
    QVERIFY(!d.ok());
    QVERIFY(d.status.message.find("object space") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestCompose)
#include "test_compose.moc"
