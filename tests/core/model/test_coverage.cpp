// SPDX-License-Identifier: Apache-2.0
// Coverage (core/model/coverage.h): what of the source frame a camera maps onto an area of the
// target frame, against hand-computed lattices: the 48 × 48 cells of a 64 × 64 frame are 4/3 px
// wide, so a pole line at pixel column 25.6 runs through cell column 19 (25.33…26.67 px).
#include "core/model/coverage.h"
#include "core/model/artcam.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

using namespace artcam;

namespace {
// y = H x with x = (u, v, 1) in the normalised frame: Q_i = sym(e_3 h_iᵀ).
Camera fromHomography(const Eigen::Matrix3d& h) {
  Stage stage;
  const Eigen::Vector3d w(0, 0, 1);
  for (int i = 0; i < 3; ++i) stage.q.push_back(symmetricOuter(w, h.row(i).transpose()));
  return Camera({Block{BlockKind::Position, 3}}, {stage}, {64, 64}, {64, 64});
}
constexpr int kCells = 48 * 48;
}  // namespace

class TestCoverage : public QObject {
  Q_OBJECT

 private slots:
  void theIdentityCoversEveryCell() {
    const Coverage c = measureCoverage(fromHomography(Eigen::Matrix3d::Identity()));
    QVERIFY(c.checked);
    QCOMPARE(c.cells, kCells);
    QCOMPARE(c.covering, kCells);
    QVERIFY(c.status().ok);
    QVERIFY(c.warning().empty());
  }

  // A valid camera whose picture misses the target frame: a warning, not a refusal (issue 44).
  void aShiftOffTheFrameRendersNothingAndIsWarnedAbout() {
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(0, 2) = 6.0;  // three frame widths to the right (the normalised frame is 2 wide)
    const Camera camera = fromHomography(h);
    const Coverage c = measureCoverage(camera);
    QCOMPARE(c.covering, 0);
    QVERIFY(c.missesTarget());
    QVERIFY2(c.status().ok, c.status().message.c_str());
    QVERIFY2(c.warning().find("renders nothing inside the target frame") != std::string::npos,
             c.warning().c_str());
    const Artcam doc(camera);
    QVERIFY(validateArtcam(doc).ok);
    QCOMPARE(cameraWarnings(doc).size(), size_t{1});
  }

  void aStrongZoomStillCovers() {
    // 200× about the centre: every mapped cell corner lies outside the target frame, but the
    // central cells' images span it.
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(0, 0) = h(1, 1) = 200.0;
    const Coverage c = measureCoverage(fromHomography(h));
    QVERIFY(c.covering > 0);
    QVERIFY(c.covering <= 4);  // only the cells touching the centre meet a 1/200 window
    QVERIFY(c.status().ok);
  }

  void aPoleLineLosesOneColumnOfCells() {
    // Denominator u + 0.2: zero at u = -0.2, pixel x = 32 - 0.2·32 = 25.6.
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(2, 0) = 1.0;
    h(2, 2) = 0.2;
    const Coverage c = measureCoverage(fromHomography(h));
    QCOMPARE(c.across_pole, 48);
    QCOMPARE(c.pole_pixel.x(), 19.5 * 64.0 / 48.0);
    QVERIFY(c.status().ok);
    const std::string warning = c.warning();
    QVERIFY2(warning.find("pole crosses the source frame near pixel (26, ") != std::string::npos,
             warning.c_str());
  }

  void everythingOntoALineIsRefused() {
    // x' = u/u = 1, y' = v/u: the frame collapses onto the line x' = 1. The lattice column at
    // u = 0 (point 24 of 49) has weight 0: its two neighbouring cell columns have no finite
    // corner there; every other cell is flat.
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    h(0, 0) = 1.0;
    h(1, 1) = 1.0;
    h(2, 0) = 1.0;
    const Coverage c = measureCoverage(fromHomography(h));
    QCOMPARE(c.covering, 0);
    QCOMPARE(c.non_finite, 2 * 48);
    QCOMPARE(c.flat, kCells - 2 * 48);
    QVERIFY(c.status().message.find("onto a line or a point") != std::string::npos);
  }

  void aZeroDenominatorHasNoFinitePoint() {
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(2, 2) = 0.0;
    const Coverage c = measureCoverage(fromHomography(h));
    QCOMPARE(c.non_finite, kCells);
    QVERIFY(c.status().message.find("no point of the source frame maps to a finite position") !=
            std::string::npos);
  }

  void aChainIsMeasuredThroughEveryStage() {
    // Off the frame and back: each stage alone renders nothing, the chain is the identity.
    Eigen::Matrix3d there = Eigen::Matrix3d::Identity(), back = there;
    there(0, 2) = 6.0;
    back(0, 2) = -6.0;
    const Camera a = fromHomography(there), b = fromHomography(back);
    const Camera chain({Block{BlockKind::Position, 3}}, {a.stages()[0], b.stages()[0]}, {64, 64}, {64, 64});
    QCOMPARE(measureCoverage(chain).covering, kCells);
    QCOMPARE(measureCoverage(a).covering, 0);
  }

  void aColourCameraIsMeasuredOnItsPositionBlock() {
    // Colour first, position second (offset 4): the position forms are the homography's,
    // embedded; the colour outputs pass colour through (c_i · w).
    for (const double shift : {0.0, 6.0}) {
      Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
      h(0, 2) = shift;
      const Camera plain = fromHomography(h);
      Stage stage;
      const auto unit = [](int i) { return Eigen::VectorXd::Unit(7, i); };
      for (int i = 0; i < 4; ++i) stage.q.push_back(symmetricOuter(unit(i), unit(6)));
      for (int r = 0; r < 3; ++r) {
        Eigen::MatrixXd q = Eigen::MatrixXd::Zero(7, 7);
        q.block<3, 3>(4, 4) = plain.stages()[0].q[static_cast<size_t>(r)];
        stage.q.push_back(q);
      }
      const Camera coloured({Block{BlockKind::Colour, 4}, Block{BlockKind::Position, 3}}, {stage}, {64, 64}, {64, 64});
      const Coverage c = measureCoverage(coloured);
      QVERIFY(c.checked);
      QCOMPARE(c.covering, shift == 0.0 ? kCells : 0);
    }
  }

  void theWidestCameraIsChecked() {
    // Position, colour, depth and second colour: 13 elements, evaluated compiled.
    const Camera wide = Camera::identity({Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4},
                                          Block{BlockKind::Depth, 2}, Block{BlockKind::SecondColour, 4}},
                                         {64, 64}, {64, 64});
    const Coverage c = measureCoverage(wide);
    QVERIFY(c.checked);
    QCOMPARE(c.covering, kCells);
  }

  void objectSpaceCamerasAreNotChecked() {
    const Camera c = Camera::identity({Block{BlockKind::Position, 4}}, {}, {});
    QVERIFY(!measureCoverage(c).checked);
    QVERIFY(measureCoverage(c).status().ok);
  }
};

QTEST_GUILESS_MAIN(TestCoverage)
#include "test_coverage.moc"
