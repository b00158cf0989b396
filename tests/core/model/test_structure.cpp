// SPDX-License-Identifier: Apache-2.0
// Structure analysis: zero blocks and the geometry ladder identity ⊂ … ⊂ rational.
#include "core/model/structure.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

using namespace artcam;

namespace {
Camera fromHomography(const Eigen::Matrix3d& h, const Eigen::Vector3d& l) {
  Stage stage;
  for (int i = 0; i < 3; ++i) stage.q.push_back(symmetricOuter(l, h.row(i).transpose()));
  return Camera({Block{BlockKind::Position, 3}}, {stage}, {64, 64}, {64, 64});
}
}  // namespace

class TestStructure : public QObject {
  Q_OBJECT

 private slots:
  void classifiesTheLadder() {
    const Eigen::Vector3d inf(0, 0, 1);
    QCOMPARE(analyseStructure(fromHomography(Eigen::Matrix3d::Identity(), inf)).geometry,
             GeometryClass::Identity);
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t(0, 2) = 0.25;
    QCOMPARE(analyseStructure(fromHomography(t, inf)).geometry, GeometryClass::Translation);
    Eigen::Matrix3d a = t;
    a(0, 1) = 0.3;
    QCOMPARE(analyseStructure(fromHomography(a, inf)).geometry, GeometryClass::Affine);
    Eigen::Matrix3d h = a;
    h(2, 0) = 0.1;
    QCOMPARE(analyseStructure(fromHomography(h, inf)).geometry, GeometryClass::Homography);
    QCOMPARE(analyseStructure(test::randomRationalCamera({64, 64}, {64, 64}, 0.2)).geometry,
             GeometryClass::Rational);
  }

  // Q_i = sym(l h_iᵀ) is the same homography for any line l (eq 1): found for all of them,
  // and the recovered matrix maps points like the original.
  void findsHomographyWithAnyCommonFactor() {
    Eigen::Matrix3d h;
    h << 1.1, 0.2, 0.1, -0.1, 0.9, 0.05, 0.08, -0.06, 1.0;
    for (int t = 0; t < 10; ++t) {
      const Eigen::Vector3d l(test::uniform(-1, 1), test::uniform(-1, 1), test::uniform(-1, 1));
      const CameraStructure s = analyseStructure(fromHomography(h, l));
      QCOMPARE(s.geometry, GeometryClass::Homography);
      const Eigen::Vector3d x(0.3, -0.7, 1.0);
      const Eigen::Vector3d want = h * x;
      const Eigen::Vector3d got = s.homography * x;
      QVERIFY((want.head<2>() / want[2] - got.head<2>() / got[2]).norm() < 1e-12);
    }
  }

  void reportsZeroBlocksAndCoupling() {
    const Block pos{BlockKind::Position, 3}, col{BlockKind::Colour, 4};
    Camera cam = Camera::identity({pos, col}, {64, 64}, {64, 64});
    CameraStructure s = analyseStructure(cam);
    QCOMPARE(s.geometry, GeometryClass::Identity);
    QVERIFY(!s.geometry_depends_on_attributes);
    QVERIFY(!s.attributes_change);
    QVERIFY(s.nonzero[0][0][0][0]);   // Q_1 has pp terms
    QVERIFY(!s.nonzero[0][0][1][1]);  // and no cc terms
    cam.stages()[0].q[0](0, 3) = cam.stages()[0].q[0](3, 0) = 0.1;  // colour drives x
    s = analyseStructure(cam);
    QVERIFY(s.geometry_depends_on_attributes);
    cam = Camera::identity({pos, col}, {64, 64}, {64, 64});
    cam.stages()[0].q[3] *= 0.5;  // darken red
    s = analyseStructure(cam);
    QVERIFY(s.attributes_change);
    QVERIFY(!s.geometry_depends_on_attributes);
  }

  // Eq 8/9 divides by p3·c4, which lives in the position–colour coupling: not degenerate.
  void couplingDenominatorIsNotDegenerate() {
    Camera cam = Camera::identity({Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}},
                                  {8, 8}, {8, 8});
    cam.stages()[0].q[2].setZero();
    cam.stages()[0].q[2](2, 6) = cam.stages()[0].q[2](6, 2) = 0.5;
    const CameraStructure s = analyseStructure(cam);
    QVERIFY(!s.degenerate);
    QVERIFY(s.geometry_depends_on_attributes);
  }

  void zeroDenominatorIsDegenerate() {
    Camera cam = Camera::identity({Block{BlockKind::Position, 3}}, {8, 8}, {8, 8});
    cam.stages()[0].q[2].setZero();
    QVERIFY(analyseStructure(cam).degenerate);
  }
};

QTEST_GUILESS_MAIN(TestStructure)
#include "test_structure.moc"
