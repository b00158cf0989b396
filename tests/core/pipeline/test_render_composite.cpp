// SPDX-License-Identifier: Apache-2.0
// Compositing through the render front door (core/pipeline/render.h): two small images made
// here, A the photo and B the second image (RenderInputs::second), through the composite camera
// of every operator; each rendered pixel equals the Porter–Duff formula computed here from the
// two pixels, divided by eq 5 (colour over its weight, the weight clamped to [0, 1] as alpha), to
// 1e-6 (float images). The colour-only path renders it; the gather path, forced, agrees; a second
// image of twice the size whose 2×2 blocks hold B's pixels renders the same (it is read scaled
// to the photo's frame), and a 1×1 one covers the whole frame; without a second image the render
// is refused.
#include "core/colour/composite.h"
#include "core/pipeline/render.h"
#include "tests/support/porter_duff.h"

#include <QtTest/QtTest>

#include <Eigen/Core>

#include <algorithm>
#include <random>
#include <stdexcept>

using namespace artcam;
using artcam::test::kCompositeOps;
using artcam::test::porterDuff;

namespace {

using Colour = Eigen::Vector4d;

Colour pixelOf(const ImageF& image, int x, int y) {
  const float* p = image.pixel(x, y);
  return {p[0], p[1], p[2], p[3]};
}

// Premultiplied RGBA with random alphas in [0.05, 1]; the last row of `b` transparent, so
// "over" shows A alone there and "in" nothing.
ImageF randomImage(int w, int h, unsigned seed, bool transparent_last_row) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), alpha(0.05f, 1.0f);
  ImageF image(w, h, 4, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.pixel(x, y);
      const float a = transparent_last_row && y == h - 1 ? 0.0f : alpha(rng);
      for (int k = 0; k < 3; ++k) p[k] = a * unit(rng);
      p[3] = a;
    }
  return image;
}


// eq 5 on the formula: colour / weight, premultiplied again by the weight clamped to [0, 1];
// transparent where the weight is not positive.
Colour rendered(const Colour& z) {
  if (!(z[3] > 0)) return Colour::Zero();
  const double alpha = std::min(z[3], 1.0);
  return {z[0] / z[3] * alpha, z[1] / z[3] * alpha, z[2] / z[3] * alpha, alpha};
}

// The largest difference between the render and the closed form over every pixel.
double worstError(const ImageF& out, const ImageF& a, const ImageF& b, CompositeOp op, double t) {
  if (out.width != a.width || out.height != a.height || out.channels != 4) return 1e9;
  double worst = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Colour ca = pixelOf(a, x, y), cb = pixelOf(b, x, y);
      const Colour want = rendered((1 - t) * ca + t * porterDuff(op, ca, cb));
      worst = std::max(worst, (pixelOf(out, x, y) - want).cwiseAbs().maxCoeff());
    }
  return worst;
}

}  // namespace

class TestRenderComposite : public QObject {
  Q_OBJECT

 private slots:
  void everyOperatorPerPixel() {
    const ImageF a = randomImage(7, 5, 11, false), b = randomImage(7, 5, 12, true);
    RenderInputs inputs = RenderInputs::of(a);
    inputs.second = &b;
    for (const CompositeOp op : kCompositeOps)
      for (const double t : {1.0, 0.6}) {
        const Artcam camera(compositeCamera(op, t, {7, 5}));
        RenderSummary summary;
        const ImageF out = render(inputs, camera, {}, &summary);
        const QString what =
            QString("%1 t=%2").arg(QString::fromUtf8(compositeOpName(op).data())).arg(t);
        QVERIFY2(summary.path == RenderPath::ColourOnly, qPrintable(what));
        const double error = worstError(out, a, b, op, t);
        QVERIFY2(error < 1e-6, qPrintable(what + QString(": %1").arg(error)));
        // The transparent last row of B: over leaves A, in leaves nothing.
        if (op == CompositeOp::Over && t == 1.0)
          QVERIFY((pixelOf(out, 3, 4) - pixelOf(a, 3, 4)).cwiseAbs().maxCoeff() < 1e-7);
        if (op == CompositeOp::In && t == 1.0) QCOMPARE(out.pixel(3, 4)[3], 0.0f);
      }
  }

  // The gather path (geometry from position, forced) reads the second image at the source
  // point: with identity geometry it renders the same picture.
  void gatherPathAgrees() {
    const ImageF a = randomImage(6, 4, 21, false), b = randomImage(6, 4, 22, false);
    RenderInputs inputs = RenderInputs::of(a);
    inputs.second = &b;
    RenderOptions options;
    options.force_path = "gather";
    RenderSummary summary;
    const ImageF out =
        render(inputs, Artcam(compositeCamera(CompositeOp::Atop, 1.0, {6, 4})), options, &summary);
    QVERIFY(summary.path == RenderPath::Gather);
    QVERIFY(worstError(out, a, b, CompositeOp::Atop, 1.0) < 1e-6);
  }

  // A second image of another size lies over the photo's frame: one of twice the size whose
  // 2×2 blocks repeat B's pixels is read as B (bilinear between equal texels), and a 1×1 one is
  // the same colour everywhere, edges included.
  void secondImageIsScaledToThePhotosFrame() {
    const ImageF a = randomImage(5, 4, 31, false), b = randomImage(5, 4, 32, false);
    ImageF doubled(10, 8, 4, 3);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 10; ++x) std::copy_n(b.pixel(x / 2, y / 2), 4, doubled.pixel(x, y));
    const Artcam camera(compositeCamera(CompositeOp::Over, 1.0, {5, 4}));
    RenderInputs inputs = RenderInputs::of(a);
    inputs.second = &doubled;
    QVERIFY(worstError(render(inputs, camera), a, b, CompositeOp::Over, 1.0) < 1e-6);

    ImageF one(1, 1, 4, 3);
    const float c[4] = {0.2f, 0.1f, 0.4f, 0.5f};
    std::copy_n(c, 4, one.pixel(0, 0));
    ImageF flat(5, 4, 4, 3);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) std::copy_n(c, 4, flat.pixel(x, y));
    inputs.second = &one;
    QVERIFY(worstError(render(inputs, camera), a, flat, CompositeOp::Over, 1.0) < 1e-6);
  }

  void refusedWithoutASecondImage() {
    const ImageF a = randomImage(4, 3, 41, false);
    const Artcam camera(compositeCamera(CompositeOp::Over, 1.0, {4, 3}));
    QVERIFY(needsLinearPhoto(camera));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, render(RenderInputs::of(a), camera));
  }
};

QTEST_GUILESS_MAIN(TestRenderComposite)
#include "test_render_composite.moc"
