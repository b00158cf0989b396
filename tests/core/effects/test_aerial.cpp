// SPDX-License-Identifier: Apache-2.0
// Aerial perspective (aerial.h) against the closed-form log model of the paper's §3:
// c' = c·(1 − t·l*) + t·l*·a·haze with l* = ln(d/near)/ln(far/near), per pixel in double.
#include "core/effects/aerial.h"
#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

class TestAerial : public QObject {
  Q_OBJECT

 private slots:
  void logFitIsCloseAndPoleFree() {
    for (const auto& [near, far] : {std::pair{1.0, 100.0}, std::pair{2.0, 20.0}, std::pair{0.5, 1000.0}}) {
      const LogDepthFit fit = fitLogDepth(near, far);
      qInfo("log-depth fit over [%g, %g]: max error %.4g, rms %.4g (units of l in [0, 1])", near,
            far, fit.max_error, fit.rms_error);
      // Independent check of the reported figure on other samples.
      double worst = 0.0;
      for (int i = 0; i <= 997; ++i) {
        const double d = near + (far - near) * i / 997.0;
        const Eigen::Vector2d x(d, 1.0);
        const double l = x.dot(fit.numerator * x) / x.dot(fit.denominator * x);
        worst = std::max(worst, std::abs(l - std::log(d / near) / std::log(far / near)));
      }
      QVERIFY(worst <= fit.max_error * 1.05 + 1e-12);
      QVERIFY2(fit.max_error < 0.06, qPrintable(QString("max error %1").arg(fit.max_error)));
    }
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, fitLogDepth(5.0, 1.0));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, fitLogDepth(0.0, 1.0));
  }

  void renderMatchesClosedForm() {
    const FrameSize size{31, 19};
    AerialParams p;
    p.haze = {0.6, 0.7, 0.9};
    p.strength = 0.8;
    p.near = 2.0;
    p.far = 60.0;
    LogDepthFit fit;
    const Camera cam = aerialPerspectiveCamera(p, size, size, &fit);
    const CameraStructure st = analyseStructure(cam);
    QCOMPARE(st.geometry, GeometryClass::Identity);
    QVERIFY(!st.geometry_depends_on_attributes);
    ImageF src(size.width, size.height, 4, 3), depth(size.width, size.height, 1);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const float a = static_cast<float>(test::uniform(0.3, 1.0));
        for (int c = 0; c < 3; ++c) src.pixel(x, y)[c] = a * static_cast<float>(test::uniform(0, 1));
        src.pixel(x, y)[3] = a;
        depth.pixel(x, y)[0] = static_cast<float>(p.near * std::pow(p.far / p.near, test::uniform(0, 1)));
      }
    AttributedSummary summary;
    const AttributedImage out = renderAttributed(src, &depth, cam, {}, &summary);
    QCOMPARE(summary.path, AttributedPath::ColourOnly);
    double worst = 0.0, worst_log = 0.0;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const float* c = src.pixel(x, y);
        const double l = std::log(depth.pixel(x, y)[0] / p.near) / std::log(p.far / p.near);
        for (int k = 0; k < 3; ++k) {
          const double expected = c[k] * (1 - p.strength * l) + p.strength * l * c[3] * p.haze[k];
          worst = std::max(worst, std::abs(out.colour.pixel(x, y)[k] - expected));
        }
        QCOMPARE(out.colour.pixel(x, y)[3], c[3]);
        worst_log = std::max(worst_log, std::abs(out.depth.pixel(x, y)[0] - l));
      }
    // The colour error is the log fit's error scaled by t·|haze − c| ≤ t.
    qInfo("aerial render vs closed-form log: max colour error %.4g (fit max %.4g)", worst, fit.max_error);
    QVERIFY(worst <= p.strength * fit.max_error + 1e-5);
    QVERIFY(worst_log <= fit.max_error + 1e-5);
  }
};

QTEST_GUILESS_MAIN(TestAerial)
#include "test_aerial.moc"
