// SPDX-License-Identifier: Apache-2.0
// Depth of field (depth_of_field.h): the σ² stage against its closed form (thin lens, linear
// and between); the exact blur against a per-pixel double-precision Gaussian written here; the
// fast stack against the exact blur (PSNR); the halo rule: a sharp foreground must not bleed into
// the blurred background beyond a threshold, and without the rule it would (so the test can fail).
#include "core/effects/depth_of_field.h"
#include "core/effects/effect_table.h"
#include "core/render/attributed.h"
#include "tests/core/render/photo_fixture.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

double psnr(const ImageF& a, const ImageF& b) {
  double se = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = a.data[i] - b.data[i];
    se += d * d;
  }
  return 10.0 * std::log10(1.0 / (se / (a.data.size() * 0.75)));
}

// Background (blue, blurred σ_b) on the left, sharp red foreground from column `edge`.
void edgeScene(int w, int h, int edge, float sigma_b, ImageF& rgba, ImageF& sigma) {
  rgba = ImageF(w, h, 4, 3);
  sigma = ImageF(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = rgba.pixel(x, y);
      const bool fg = x >= edge;
      p[0] = fg ? 1.0f : 0.0f;
      p[2] = fg ? 0.0f : 1.0f;
      p[3] = 1.0f;
      sigma.pixel(x, y)[0] = fg ? 0.0f : sigma_b;
    }
}

double worstRedInBackground(const ImageF& out, int edge) {
  double worst = 0.0;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < edge; ++x) worst = std::max(worst, static_cast<double>(out.pixel(x, y)[0]));
  return worst;
}

}  // namespace

class TestDepthOfField : public QObject {
  Q_OBJECT

 private slots:
  void varianceStageIsClosedForm() {
    const FrameSize size{64, 48};
    const DepthOfFieldParams p{3.0, 0.02};
    const Camera cam = depthOfFieldCamera(p, size, size);
    for (int i = 0; i < 100; ++i) {
      const double d = test::uniform(0.3, 50.0);
      Eigen::VectorXd x(9);
      x << test::uniform(-1, 1), test::uniform(-1, 1), 1, 0.2, 0.3, 0.4, 1, d, 1;
      const Eigen::VectorXd y = cam.evaluate(x);
      const double expected = p.blur * p.blur * (d - p.focus) * (d - p.focus) / (d * d);
      QVERIFY(std::abs(y[7] - expected) <= 1e-12 * (1 + expected));
      QVERIFY(std::abs(y[3] - 0.2) < 1e-12);  // colour untouched
    }
  }

  // The non-linear option (header): σ² = k²(d − f)²/((1 − γ)f + γd)². Checked against the
  // closed forms of the two named models and a blend, and by what each model means: the linear
  // one gains k per focus distance behind the focal plane, the thin lens tends to k at infinity.
  void lensModelsAreClosedForm() {
    const FrameSize size{64, 48};
    const double f = 2.5, k = 0.03;
    const auto variance = [&](double gamma, double d) {
      const Camera cam = depthOfFieldCamera({f, k, gamma}, size, size);
      Eigen::VectorXd x(9);
      x << 0.1, -0.2, 1, 0.2, 0.3, 0.4, 1, d, 1;
      return cam.evaluate(x)[7];
    };
    for (const double gamma : {0.0, 0.25, 1.0})
      for (int i = 0; i < 50; ++i) {
        const double d = test::uniform(0.2, 80.0);
        const double den = (1 - gamma) * f + gamma * d;
        const double expected = k * k * (d - f) * (d - f) / (den * den);
        QVERIFY2(std::abs(variance(gamma, d) - expected) <= 1e-12 * (1 + expected),
                 qPrintable(QString("γ %1 d %2").arg(gamma).arg(d)));
      }
    // Linear: σ = k·|d − f|/f, so one focus distance further adds exactly k.
    QVERIFY(std::abs(std::sqrt(variance(0.0, 3 * f)) - std::sqrt(variance(0.0, 2 * f)) - k) <
            1e-12);
    QVERIFY(std::abs(std::sqrt(variance(0.0, 0.5 * f)) - 0.5 * k) < 1e-12);
    // Thin lens: σ → k far away, and in front σ = k·(f/d − 1).
    QVERIFY(std::abs(std::sqrt(variance(1.0, 1e9)) - k) < 1e-8);
    QVERIFY(std::abs(std::sqrt(variance(1.0, 0.5 * f)) - k) < 1e-12);
    // Both are sharp at the focus and agree to first order near it (same slope k/f).
    QVERIFY(variance(0.0, f) == 0.0 && variance(1.0, f) == 0.0);
    const double e = 1e-4 * f;
    QVERIFY(std::abs(std::sqrt(variance(0.0, f + e)) - std::sqrt(variance(1.0, f + e))) <
            1e-3 * k * e / f);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, depthOfFieldCamera({f, k, 1.5}, size, size));
  }

  // The paper's §3 form, blur proportional to depth: focus 0 with the linear model gives
  // σ = k·d exactly (σ² = k²d²), sharp only where there is no depth; a thin lens focused at 0
  // is refused, since it would blur every depth alike.
  void blurProportionalToDepth() {
    const FrameSize size{64, 48};
    const double k = 0.004;
    const Camera cam = depthOfFieldCamera({0.0, k, 0.0}, size, size);
    for (const double d : {0.0, 0.5, 1.0, 7.25, 40.0}) {
      Eigen::VectorXd x(9);
      x << 0.3, 0.1, 1, 0.2, 0.3, 0.4, 1, d, 1;
      const double v = cam.evaluate(x)[7];
      QVERIFY2(std::abs(v - k * k * d * d) <= 1e-15 * (1 + d * d), qPrintable(QString::number(d)));
    }
    // Through the effects table and the pixel conversion: σ_px = k·d·max(w, h)/2.
    const Artcam effect = buildEffect("depth-of-field", {{"focus", {0.0}}, {"thin-lens", {0.0}},
                                                         {"blur", {k}}}, size);
    QCOMPARE(effect.depth_output, DepthOutput::BlurVariance);
    ImageF variance(size.width, size.height, 1);
    for (float& v : variance.data) v = static_cast<float>(k * k * 10.0 * 10.0);  // depth 10
    QVERIFY(std::abs(sigmaPixelsFromVariance(variance).data[0] - k * 10.0 * 32.0) < 1e-4);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, depthOfFieldCamera({0.0, k, 1.0}, size, size));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect("depth-of-field", {{"focus", {0.0}}}, size));
  }

  void exactBlurMatchesDirectGaussian() {
    const int w = 23, h = 17;
    ImageF rgba(w, h, 4, 3), sigma(w, h, 1);
    for (float& v : rgba.data) v = static_cast<float>(test::uniform(0, 1));
    for (float& s : sigma.data) s = static_cast<float>(test::uniform(0.0, 3.0));
    BlurOptions o;
    o.halo_ratio = 0.5;
    const ImageF out = exactBlur(rgba, sigma, o);
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double s = sigma.pixel(x, y)[0];
        for (int c = 0; c < 4; ++c) {
          double expected = rgba.pixel(x, y)[c];
          if (s >= o.min_sigma) {
            double num = 0, den = 0;
            for (int yy = 0; yy < h; ++yy)
              for (int xx = 0; xx < w; ++xx) {
                const double dx = xx - x, dy = yy - y;
                if (std::abs(dx) > std::ceil(3 * s) || std::abs(dy) > std::ceil(3 * s)) continue;
                if (sigma.pixel(xx, yy)[0] < o.halo_ratio * s) continue;
                const double g = std::exp(-(dx * dx + dy * dy) / (2 * s * s));
                num += g * rgba.pixel(xx, yy)[c];
                den += g;
              }
            expected = num / den;
          }
          worst = std::max(worst, std::abs(out.pixel(x, y)[c] - expected));
        }
      }
    QVERIFY2(worst < 1e-5, qPrintable(QString("max error %1").arg(worst)));
  }

  void stackApproachesExact() {
    ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const ImageF rgba = rgbaFromImage(photo);
    // Depth rising left to right through the focus: σ from 0 to 8 px.
    const FrameSize size{rgba.width, rgba.height};
    ImageF depth(size.width, size.height, 1);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        depth.pixel(x, y)[0] = 1.0f + 9.0f * (x + 0.5f) / size.width;
    DepthOfFieldParams p{1.5, 8.0 / (std::max(size.width, size.height) / 2.0) / 0.9};
    const AttributedImage variance =
        renderAttributed(rgba, &depth, depthOfFieldCamera(p, size, size));
    const ImageF sigma = sigmaPixelsFromVariance(variance.depth);
    const ImageF exact = exactBlur(rgba, sigma);
    const ImageF fast = stackBlur(rgba, sigma);
    const double db = psnr(exact, fast);
    qInfo("depth of field on coffee.png (σ 0..8 px): stack vs exact PSNR %.2f dB", db);
    QVERIFY2(db > 35.0, qPrintable(QString("PSNR %1").arg(db)));
  }

  // A scattered σ field (8×8 tiles of random σ in [0, 6], a quarter of them sharp) makes every
  // band of the stack use scattered levels over scattered column ranges, and tile edges test the
  // halo masks: still close to the exact blur.
  void stackApproachesExactOnScatteredSigma() {
    const ImageF photo = rgbaFromImage(test::readLinearPhoto(test::resourcePath("coffee.png")));
    QVERIFY(!photo.empty());
    ImageF sigma(photo.width, photo.height, 1);
    std::vector<float> tiles(static_cast<size_t>((photo.width / 8 + 1) * (photo.height / 8 + 1)));
    for (float& t : tiles)
      t = test::uniform(0, 1) < 0.25 ? 0.0f : static_cast<float>(test::uniform(0.0, 6.0));
    for (int y = 0; y < photo.height; ++y)
      for (int x = 0; x < photo.width; ++x)
        sigma.pixel(x, y)[0] = tiles[static_cast<size_t>((y / 8) * (photo.width / 8 + 1) + x / 8)];
    BlurOptions two;
    two.threads = 2;
    const double db = psnr(exactBlur(photo, sigma, two), stackBlur(photo, sigma, two));
    qInfo("scattered σ 0..6 px on coffee.png: stack vs exact PSNR %.2f dB", db);
    QVERIFY2(db > 35.0, qPrintable(QString("PSNR %1").arg(db)));
  }

  void noHaloOfSharpForeground() {
    ImageF rgba, sigma;
    const int edge = 40;
    edgeScene(80, 24, edge, 6.0f, rgba, sigma);
    const double threshold = 0.02;
    const double exact = worstRedInBackground(exactBlur(rgba, sigma), edge);
    const double fast = worstRedInBackground(stackBlur(rgba, sigma), edge);
    BlurOptions plain;
    plain.halo_ratio = 0.0;
    const double without = worstRedInBackground(exactBlur(rgba, sigma, plain), edge);
    qInfo("red bled into the background: exact %.4f, stack %.4f, without the rule %.4f", exact,
          fast, without);
    QVERIFY(exact <= threshold);
    QVERIFY(fast <= threshold);
    QVERIFY(without > 0.2);  // the scene does detect a halo
  }
};

QTEST_GUILESS_MAIN(TestDepthOfField)
#include "test_depth_of_field.moc"
