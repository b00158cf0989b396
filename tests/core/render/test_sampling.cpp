// SPDX-License-Identifier: Apache-2.0
// Filters (sampling.h): pixel centres at i + 0.5, exact reproduction where the theory says so,
// transparent outside the source.
#include "core/sampling/sampling.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"

#include <QtTest/QtTest>

#include <Eigen/LU>

#include <cmath>

using namespace artcam;

namespace {

const FrameSize kSize{96, 64};

ImageF ramp() {
  ImageF img(kSize.width, kSize.height, 1);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) img.pixel(x, y)[0] = static_cast<float>(0.01 * x + 0.005 * y + 0.1);
  return img;
}

}  // namespace

class TestSampling : public QObject {
  Q_OBJECT

 private slots:
  void weightsSumToOneAndInterpolate() {
    for (double t : {0.0, 0.1, 0.5, 0.77, 0.999}) {
      double w[4];
      cubicWeights(t, w);
      QVERIFY(std::abs(w[0] + w[1] + w[2] + w[3] - 1.0) < 1e-15);
      // Reproduces x and x² (Keys a = −0.5 is third-order accurate).
      QVERIFY(std::abs(-w[0] + w[2] + 2 * w[3] - t) < 1e-14);
      QVERIFY(std::abs(w[0] + w[2] + 4 * w[3] - t * t) < 1e-14);
    }
  }

  // Integer shifts land on pixel centres: every filter returns the source values exactly.
  void integerTranslationIsExact() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    const double s = std::max(kSize.width, kSize.height) / 2.0;  // normalised units per pixel⁻¹
    h(0, 2) = 3.0 / s;
    h(1, 2) = -2.0 / s;
    const Camera camera = test::homographyCamera(h, kSize, kSize);
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      const ImageF out = warpImage(src, camera, o);
      for (int y = 0; y < out.height - 2; ++y)
        for (int x = 3; x < out.width; ++x)
          for (int c = 0; c < 3; ++c)
            QCOMPARE(out.pixel(x, y)[c], src.pixel(x - 3, y + 2)[c]);
      QCOMPARE(out.pixel(1, 10)[3], 0.0f);   // shifted in from outside: transparent
      QCOMPARE(out.pixel(10, 10)[3], 1.0f);
    }
  }

  // Bicubic (and bilinear) reproduce a linear ramp exactly wherever all taps are inside.
  void bicubicReproducesRamp() {
    const ImageF src = ramp();
    Eigen::Matrix3d h;
    h << 0.9, 0.1, 0.02, -0.08, 1.05, -0.03, 0.05, 0.04, 1.0;
    const Camera camera = test::homographyCamera(h, kSize, kSize);
    const Eigen::Matrix3d px = pixelFromNormalizedMatrix(kSize) * h * normalizedFromPixelMatrix(kSize);
    const Eigen::Matrix3d inv = px.inverse();
    for (Filter f : {Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      const ImageF out = warpImage(src, camera, o);
      int checked = 0;
      double max_err = 0.0;
      for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
          const Eigen::Vector3d s = inv * Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
          const double sx = s.x() / s.z() - 0.5, sy = s.y() / s.z() - 0.5;  // index space
          if (sx < 1.0 || sy < 1.0 || sx > kSize.width - 3.0 || sy > kSize.height - 3.0) continue;
          max_err = std::max(max_err, std::abs(out.pixel(x, y)[0] - (0.01 * sx + 0.005 * sy + 0.1)));
          QCOMPARE(out.pixel(x, y)[1], 1.0f);
          ++checked;
        }
      QVERIFY(checked > kSize.width * kSize.height / 2);
      QVERIFY2(max_err < 2e-6, qPrintable(QString("%1: %2").arg(filterName(f).data()).arg(max_err)));
    }
  }

  // Nearest returns the value of the pixel whose square contains the source point.
  void nearestPicksContainingPixel() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    const Sampler sampler(src, Filter::Nearest);
    float out[4];
    sampler.sample(10.0, 5.999, out);
    QCOMPARE(out[0], src.pixel(10, 5)[0]);
    sampler.sample(10.999, 6.0, out);
    QCOMPARE(out[0], src.pixel(10, 6)[0]);
    QCOMPARE(out[3], 1.0f);
    sampler.sample(-0.001, 3.0, out);
    QCOMPARE(out[3], 0.0f);
    sampler.sample(kSize.width, 3.0, out);
    QCOMPARE(out[3], 0.0f);
  }

  // At the border bilinear fades: half a pixel outside the edge centre, coverage is 1/2.
  void borderFadesInAlpha() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    const Sampler sampler(src, Filter::Bilinear);
    float out[4];
    sampler.sample(0.0, 10.5, out);  // between the edge pixel's centre and the outside
    QVERIFY(std::abs(out[3] - 0.5f) < 1e-6f);
    QVERIFY(std::abs(out[0] - 0.5f * src.pixel(0, 10)[0]) < 1e-6f);
    sampler.sample(-0.5, 10.5, out);
    QCOMPARE(out[3], 0.0f);
    sampler.sample(std::nan(""), 10.5, out);
    QCOMPARE(out[3], 0.0f);
    sampler.sample(1e300, -1e300, out);
    QCOMPARE(out[0], 0.0f);
  }
};

QTEST_GUILESS_MAIN(TestSampling)
#include "test_sampling.moc"
