// SPDX-License-Identifier: Apache-2.0
// The map from an RGB space given by its chromaticities into the working space (linear Rec.709,
// D65) against published matrices: ACEScg (AP1, ACES white) to linear Rec.709 with Bradford
// adaptation as the Academy's and OpenColorIO's ACES configs give it (to the 5 decimals they
// print), and Display P3 (D65, no adaptation) to sRGB as Apple and the CSS Color 4
// specification publish it.
#include "core/colour/chromaticities.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

const Chromaticities kAcescg{{0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767}};
const Chromaticities kDisplayP3{{0.680, 0.320, 0.265, 0.690, 0.150, 0.060, 0.3127, 0.3290}};

double worstDifference(const Matrix3& a, const Matrix3& b) {
  double worst = 0;
  for (size_t k = 0; k < 9; ++k) worst = std::max(worst, std::fabs(a[k] - b[k]));
  return worst;
}

}  // namespace

class TestChromaticities : public QObject {
  Q_OBJECT
 private slots:
  void acescgToRec709IsThePublishedBradfordMatrix() {
    const Matrix3 published{1.70505,  -0.62179, -0.08326, -0.13026, 1.14080,
                            -0.01055, -0.02400, -0.12897, 1.15297};
    const double worst = worstDifference(workingFromChromaticities(kAcescg), published);
    QVERIFY2(worst < 1e-4, qPrintable(QString::number(worst)));
  }

  void displayP3ToSrgbIsThePublishedMatrix() {
    // CSS Color 4's P3 → sRGB (linear), computed from the same primaries without adaptation.
    const Matrix3 published{1.2249401, -0.2249404, 0.0,        -0.0420569, 1.0420571,
                            0.0,       -0.0196376, -0.0786361, 1.0982735};
    const double worst = worstDifference(workingFromChromaticities(kDisplayP3), published);
    QVERIFY2(worst < 1e-5, qPrintable(QString::number(worst)));
  }

  void rec709IsTheIdentityAndTheInverseUndoes() {
    QVERIFY(Chromaticities::rec709().isRec709());
    QVERIFY(!kAcescg.isRec709());
    const Matrix3 identity{1, 0, 0, 0, 1, 0, 0, 0, 1};
    QVERIFY(worstDifference(workingFromChromaticities(Chromaticities::rec709()), identity) < 1e-12);
    float px[4] = {0.2f, 0.7f, -0.1f, 0.5f};  // RGBA, alpha untouched
    applyMatrix(workingFromChromaticities(kAcescg), px, 1, 4, 3);
    applyMatrix(chromaticitiesFromWorking(kAcescg), px, 1, 4, 3);
    QVERIFY(std::fabs(px[0] - 0.2f) < 1e-6 && std::fabs(px[1] - 0.7f) < 1e-6 &&
            std::fabs(px[2] + 0.1f) < 1e-6);
    QCOMPARE(px[3], 0.5f);
  }

  // A matrix from the working space gives back the primaries it was made from (P3, D65: no
  // adaptation to undo).
  void chromaticitiesOfAMatrixAreItsPrimaries() {
    const auto found = chromaticitiesOfMatrix(chromaticitiesFromWorking(kDisplayP3));
    QVERIFY(found);
    for (size_t k = 0; k < 8; ++k)
      QVERIFY2(std::fabs(found->xy[k] - kDisplayP3.xy[k]) < 1e-9, found->describe().c_str());
    QVERIFY(!chromaticitiesOfMatrix(Matrix3{1, 0, 0, 0, 1, 0, 0, 0, 0}));
  }

  void degenerateChromaticitiesAreInvalid() {
    QVERIFY(kAcescg.valid());
    Chromaticities zero_y = kAcescg;
    zero_y.xy[3] = 0.0;
    QVERIFY(!zero_y.valid());
    const Chromaticities on_a_line{{0.2, 0.2, 0.3, 0.3, 0.4, 0.4, 0.3127, 0.3290}};
    QVERIFY(!on_a_line.valid());
    Chromaticities nan = kAcescg;
    nan.xy[0] = std::nan("");
    QVERIFY(!nan.valid());
  }
};

QTEST_GUILESS_MAIN(TestChromaticities)
#include "test_chromaticities.moc"
