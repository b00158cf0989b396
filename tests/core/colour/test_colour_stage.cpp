// SPDX-License-Identifier: Apache-2.0
// withColourBlock (core/colour/colour_stage.h): the studio's camera = geometry + fitted colour
// block. Checked by evaluating points: positions as the geometry alone gives them (one and two
// stages), colours as the 3×3 matrix applied by hand, an existing colour block replaced (not
// composed), and refusals for cameras it cannot join.
#include "core/colour/colour_map.h"
#include "core/model/camera.h"
#include "core/colour/colour_stage.h"

#include <QtTest/QtTest>

#include <stdexcept>

using namespace artcam;

namespace {

const FrameSize kFrame{320, 240};

Camera colourBlockOf(const Eigen::Matrix3d& m) {
  ColourMap map;
  map.model = ColourModel::Linear;
  map.m = m;
  return colourCamera(map, kFrame);
}

Eigen::Matrix3d someMatrix(double t) {
  Eigen::Matrix3d m;
  m << 0.8 + t, 0.1, 0.05, 0.05, 0.7, 0.2 - t, 0.1, t, 0.9;
  return m;
}

// A rational lens: u' = u (1 + k u) / (1 + 0.1 u), v' = v (1 + k u) / (1 + 0.1 u).
Stage lensStage(double k) {
  Stage s;
  s.q.assign(3, Eigen::MatrixXd::Zero(3, 3));
  s.q[0](0, 2) = s.q[0](2, 0) = 0.5;
  s.q[0](0, 0) = k;
  s.q[1](1, 2) = s.q[1](2, 1) = 0.5;
  s.q[1](0, 1) = s.q[1](1, 0) = 0.5 * k;
  s.q[2](2, 2) = 1.0;
  s.q[2](0, 2) = s.q[2](2, 0) = 0.05;
  return s;
}

}  // namespace

class TestColourStage : public QObject {
  Q_OBJECT

 private slots:
  void positionsKeptColoursMapped() {
    for (int stages : {1, 2}) {
      std::vector<Stage> st{lensStage(0.2)};
      if (stages == 2) st.push_back(lensStage(-0.1));
      const Camera geometry({Block{BlockKind::Position, 3}}, st, kFrame, kFrame);
      const Eigen::Matrix3d m = someMatrix(0.03);
      const Camera both = withColourBlock(geometry, colourBlockOf(m));
      QCOMPARE(both.stages().size(), size_t(stages));
      QCOMPARE(both.blocks().size(), size_t{2});
      for (const Eigen::Vector2d& uv : {Eigen::Vector2d(-0.5, 0.3), Eigen::Vector2d(0.4, -0.2)}) {
        const Eigen::Vector3d c(0.2, 0.6, 0.35);
        Eigen::VectorXd x(7);
        x << uv.x(), uv.y(), 1.0, c.x(), c.y(), c.z(), 1.0;
        const Eigen::VectorXd y = both.evaluate(x);
        const Eigen::VectorXd g = geometry.evaluate(Eigen::Vector3d(uv.x(), uv.y(), 1.0));
        QVERIFY(std::abs(y[0] - g[0]) < 1e-12 && std::abs(y[1] - g[1]) < 1e-12);
        QVERIFY((y.segment<3>(3) - m * c).norm() < 1e-12);
        QVERIFY(std::abs(y[6] - 1.0) < 1e-12);
        // Premultiplied input with alpha 0.5: colour unchanged, alpha kept.
        x.segment<4>(3) *= 0.5;
        const Eigen::VectorXd h = both.evaluate(x);
        QVERIFY((h.segment<3>(3) - m * c).norm() < 1e-12);
        QVERIFY(std::abs(h[6] - 0.5) < 1e-12);
      }
    }
  }

  void anExistingColourBlockIsReplaced() {
    const Camera first =
        withColourBlock(Camera::identity({Block{BlockKind::Position, 3}}, kFrame, kFrame),
                        colourBlockOf(someMatrix(0.1)));
    const Eigen::Matrix3d m2 = someMatrix(-0.05);
    const Camera second = withColourBlock(first, colourBlockOf(m2));
    QCOMPARE(second.dimension(), 7);  // no second colour block
    Eigen::VectorXd x(7);
    const Eigen::Vector3d c(0.7, 0.1, 0.4);
    x << 0.1, 0.2, 1.0, c.x(), c.y(), c.z(), 1.0;
    QVERIFY((second.evaluate(x).segment<3>(3) - m2 * c).norm() < 1e-12);
    double out[3];
    const double in[3] = {c.x(), c.y(), c.z()};
    QVERIFY(applyColourCamera(colourBlockOf(m2), in, out));
    QVERIFY((Eigen::Vector3d(out[0], out[1], out[2]) - m2 * c).norm() < 1e-12);
  }

  void refusesWhatItCannotJoin() {
    const Camera object = Camera::identity({Block{BlockKind::Position, 4}}, {}, {});
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             withColourBlock(object, colourBlockOf(someMatrix(0))));
    const Camera not_colour = Camera::identity({Block{BlockKind::Position, 3}}, kFrame, kFrame);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, withColourBlock(not_colour, not_colour));
  }
};

QTEST_MAIN(TestColourStage)
#include "test_colour_stage.moc"
