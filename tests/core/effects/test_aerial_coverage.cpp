// SPDX-License-Identifier: Apache-2.0
// Aerial perspective through the render front door (what `artcam preset aerial-perspective`
// and the studio call) leaves pixels without depth untouched and fades in with the depth's
// coverage: against the closed form c·hazed + (1 − c)·untouched, where hazed is the paper's
// §3 contrast fall-off with the exact logarithm (within the log fit's error).
#include "core/effects/aerial.h"
#include "core/model/artcam.h"
#include "core/pipeline/render.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

constexpr int kW = 40, kH = 6;
constexpr double kDepth = 20.0;

ImageF photo() {
  ImageF img(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      img.pixel(x, y)[0] = 0.05f + 0.02f * static_cast<float>(x % 7);
      img.pixel(x, y)[1] = 0.4f + 0.05f * static_cast<float>(y);
      img.pixel(x, y)[2] = 0.9f - 0.015f * static_cast<float>(x);
    }
  return img;
}

// Coverage by column: none for x < 10, a ramp 0 → 1 over 10 ≤ x < 30, full beyond.
double coverageAt(int x) { return std::clamp((x - 9) / 21.0, 0.0, 1.0); }

}  // namespace

class TestAerialCoverage : public QObject {
  Q_OBJECT

 private slots:
  void pixelsWithoutDepthAreUntouchedAndCoverageBlends_data() {
    QTest::addColumn<QString>("path");
    QTest::newRow("colour-only") << QString();
    QTest::newRow("gather") << QStringLiteral("gather");
  }

  void pixelsWithoutDepthAreUntouchedAndCoverageBlends() {
    QFETCH(QString, path);
    AerialParams p;
    p.strength = 0.8;
    p.near = 1.0;
    p.far = 100.0;
    LogDepthFit fit;
    const FrameSize frame{kW, kH};
    const Artcam camera(aerialPerspectiveCamera(p, frame, frame, &fit));
    const ImageF src = photo();
    // The 2-channel depth raster: (coverage·d, coverage), core/depth/depth_raster.h.
    ImageF depth(kW, kH, 2, 1);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const double c = coverageAt(x);
        depth.pixel(x, y)[0] = static_cast<float>(c * kDepth);
        depth.pixel(x, y)[1] = static_cast<float>(c);
      }
    RenderOptions options;
    options.force_path = path.toStdString();
    const ImageF out = render(RenderInputs::of(src, &depth), camera, options);
    QCOMPARE(out.width, kW);
    QCOMPARE(out.channels, 4);
    const double l = std::log(kDepth / p.near) / std::log(p.far / p.near);
    const double tolerance = p.strength * fit.max_error + 1e-5;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const double c = coverageAt(x);
        for (int k = 0; k < 3; ++k) {
          const double untouched = src.pixel(x, y)[k];
          const double hazed = untouched * (1 - p.strength * l) + p.strength * l * p.haze[k];
          const double expected = c * hazed + (1 - c) * untouched;
          const double got = out.pixel(x, y)[k];
          if (c == 0.0)
            QCOMPARE(got, untouched);  // bit-exact: not evaluated at all
          else
            QVERIFY2(std::abs(got - expected) <= tolerance,
                     qPrintable(QString("x %1 c %2 channel %3: %4 vs %5")
                                    .arg(x).arg(c).arg(k).arg(got).arg(expected)));
        }
        QCOMPARE(out.pixel(x, y)[3], 1.0f);
      }
  }

  void holesOfADepthFileAreUntouched() {
    // A 1-channel depth file: 0 is "no depth" (core/io/depth_file.h).
    AerialParams p;
    const FrameSize frame{kW, kH};
    const Artcam camera(aerialPerspectiveCamera(p, frame, frame));
    const ImageF src = photo();
    ImageF depth(kW, kH, 1);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) depth.pixel(x, y)[0] = x < 20 ? 0.0f : 50.0f;
    const ImageF out = render(RenderInputs::of(src, &depth), camera);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        for (int k = 0; k < 3; ++k) {
          if (x < 20)
            QCOMPARE(out.pixel(x, y)[k], src.pixel(x, y)[k]);
          else  // hazed towards the (bluish) haze: red of these pixels rises
            QVERIFY(k != 0 || out.pixel(x, y)[k] > src.pixel(x, y)[k] + 0.05f);
        }
  }
};

QTEST_GUILESS_MAIN(TestAerialCoverage)
#include "test_aerial_coverage.moc"
