// SPDX-License-Identifier: Apache-2.0
// Chromatic aberration both ways (chromatic.h, the paper's Fig 4): the three-RTcam layers
// against a per-channel inverse and bilinear read written here; the eq 8/9 ARTcam's point map
// against its closed form y = p·(1 + s_k·r_k).
#include "core/effects/chromatic.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

double bilinearChannel(const ImageF& img, const Eigen::Vector2d& s, int c) {
  const double fx = s.x() - 0.5, fy = s.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  double v = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int x = x0 + i, y = y0 + j;
      if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
      v += (i ? fx - x0 : 1 - (fx - x0)) * (j ? fy - y0 : 1 - (fy - y0)) * img.pixel(x, y)[c];
    }
  return v;
}

}  // namespace

class TestChromatic : public QObject {
  Q_OBJECT

 private slots:
  void rgbShiftLayersMatchPerChannelInverse() {
    const FrameSize size{50, 40};
    RgbShiftParams p;
    p.scale = {0.05, 0.0, -0.04};
    p.dx = {0.02, 0.0, -0.03};
    p.dy = {0.0, 0.01, 0.02};
    const std::vector<Camera> layers = rgbShiftLayers(p, size, size);
    for (const Camera& c : layers) {
      const CameraStructure st = analyseStructure(c);
      QVERIFY(!st.geometry_depends_on_attributes);
      QVERIFY(st.attributes_change);
    }
    ImageF src(size.width, size.height, 3);
    for (float& v : src.data) v = static_cast<float>(test::uniform(0, 1));
    const AttributedImage out = renderLayers(src, nullptr, layers);
    double worst = 0.0;
    for (int y = 3; y < size.height - 3; ++y)
      for (int x = 3; x < size.width - 3; ++x) {
        const Eigen::Vector2d t = normalizedFromPixel(size, {x + 0.5, y + 0.5});
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector2d s((t.x() - p.dx[k]) / (1 + p.scale[k]), (t.y() - p.dy[k]) / (1 + p.scale[k]));
          const double expected = bilinearChannel(src, pixelFromNormalized(size, s), k);
          worst = std::max(worst, std::abs(out.colour.pixel(x, y)[k] - expected));
        }
      }
    QVERIFY2(worst < 1e-4, qPrintable(QString("max error %1").arg(worst)));
  }

  // A layer that shrinks (blue, scale −0.06) leaves a border its channel never reaches. The
  // layers' coverage combines as the smallest: on a grey photo no pixel comes out as a
  // coloured frame (red and green without blue), border pixels are transparent, and inside the
  // frame the grey is exact.
  void shrinkingLayerLeavesNoColouredFrame() {
    const FrameSize size{60, 40};
    RgbShiftParams p;
    p.scale = {0.04, 0.0, -0.06};
    const std::vector<Camera> layers = rgbShiftLayers(p, size, size);
    ImageF grey(size.width, size.height, 3);
    for (float& v : grey.data) v = 0.5f;
    const AttributedImage out = renderLayers(grey, nullptr, layers);
    int transparent = 0;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const float* c = out.colour.pixel(x, y);
        if (c[3] <= 0.0f) {
          ++transparent;
          QVERIFY(c[0] == 0.0f && c[1] == 0.0f && c[2] == 0.0f);
          continue;
        }
        // Unpremultiplied, every channel is the photo's grey: no channel missing.
        for (int k = 0; k < 3; ++k)
          QVERIFY2(std::abs(c[k] / c[3] - 0.5f) < 1e-4f,
                   qPrintable(QString("(%1, %2) channel %3: %4 at alpha %5")
                                  .arg(x).arg(y).arg(k).arg(c[k]).arg(c[3])));
      }
    // Blue shrinks by 6 %: about 3 % of each side (1.8 and 1.2 px) has no blue: transparent.
    QVERIFY2(transparent > size.width + size.height, qPrintable(QString::number(transparent)));
  }

  // eq 8/9 through the model's evaluation (not the renderer) for random points and colours.
  void colourShiftIsEq8And9() {
    const FrameSize size{100, 80};
    const ColourShiftParams p{{0.3, -0.2, 0.1}};
    const std::vector<Camera> layers = colourShiftLayers(p, size, size);
    for (int k = 0; k < 3; ++k) {
      QVERIFY(analyseStructure(layers[k]).geometry_depends_on_attributes);
      for (int trial = 0; trial < 50; ++trial) {
        const double u = test::uniform(-1, 1), v = test::uniform(-1, 1), a = test::uniform(0.1, 1);
        const Eigen::Vector3d rgb(test::uniform(0, 1), test::uniform(0, 1), test::uniform(0, 1));
        Eigen::VectorXd x(7);
        x << u, v, 1.0, a * rgb, a;
        const Eigen::VectorXd y = layers[k].evaluate(x);
        const double g = 1.0 + p.s[k] * rgb[k];
        QVERIFY(std::abs(y[0] - u * g) < 1e-12 && std::abs(y[1] - v * g) < 1e-12);
        for (int c = 0; c < 3; ++c) QVERIFY(std::abs(y[3 + c] - (c == k ? rgb[k] : 0.0)) < 1e-12);
        QVERIFY(std::abs(y[6] - a) < 1e-12);
      }
    }
  }
};

QTEST_GUILESS_MAIN(TestChromatic)
#include "test_chromatic.moc"
