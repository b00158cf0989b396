// SPDX-License-Identifier: Apache-2.0
// The fused warp: forward differences re-anchored per span stay within 1e-6 px; every
// kernel's source positions agree with the exact double-precision inverse to 1/256 px; the seed
// check leaves Newton to few pixels; typed pixel formats agree with the float path; whole-pixel
// translations copy; anti-aliasing averages a minified pattern; the mip pyramid picks a level.
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/mapping/coordinates.h"
#include "core/render/preview.h"
#include "core/mapping/rational_map.h"
#include "core/sampling/sampling.h"
#include "core/sampling/span_sampler.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace artcam;

namespace {

struct Agreement {
  double max_px = 0.0;
  long long validity_mismatch = 0;
  long long compared = 0;
};

// Every pixel of every row: the fused kernel's positions against the exact reference.
Agreement compareWithReference(const Camera& camera, FrameSize src, FrameSize out, bool force_rational) {
  const CameraStructure structure = analyseStructure(camera);
  CoordinateOptions co;
  co.force_rational = force_rational;
  const KernelChoice choice = makeCoordinateKernel(camera, structure, src, out, co, 1);
  const auto reference = makeReferenceInverse(camera, structure, src, out);
  Agreement a;
  std::vector<Eigen::Vector2d> exact(static_cast<size_t>(out.width));
  std::vector<unsigned char> exact_ok(static_cast<size_t>(out.width));
  float sx[kSpanPixels], sy[kSpanPixels];
  unsigned char ok[kSpanPixels];
  for (int y = 0; y < out.height; ++y) {
    reference->row(y, out.width, exact.data(), exact_ok.data());
    RowState row_state;
    for (int x0 = 0; x0 < out.width; x0 += kSpanPixels) {
      const int n = std::min(kSpanPixels, out.width - x0);
      choice.kernel->span(y, x0, n, sx, sy, ok, row_state);
      for (int i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(x0 + i);
        // A preimage beyond the source's reach (2 px: the bicubic taps) renders transparent
        // either way; Newton gives up on those far out (10 frame diagonals, inverse.cpp).
        const bool reachable = exact_ok[k] && exact[k].x() > -2 && exact[k].y() > -2 &&
                               exact[k].x() < src.width + 2 && exact[k].y() < src.height + 2;
        if ((ok[i] != 0) != (exact_ok[k] != 0) && (reachable || ok[i])) ++a.validity_mismatch;
        if (!ok[i] || !exact_ok[k]) continue;
        a.max_px = std::max(a.max_px, std::hypot(sx[i] - exact[k].x(), sy[i] - exact[k].y()));
        ++a.compared;
      }
    }
  }
  return a;
}

Eigen::Matrix3d sym(int a, int b) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(a, b) += 0.5;
  m(b, a) += 0.5;
  return m;
}

}  // namespace

class TestFused : public QObject {
  Q_OBJECT

 private slots:
  // Forward differences along a 6000-pixel row, re-anchored every span, against direct
  // evaluation of the ratio of quadratic forms (eq 1): the drift stays below 1e-6 px.
  void forwardDifferencesStayWithinBudget() {
    const FrameSize size{6000, 4000};
    test::rng().seed(21);
    const RationalMap map(test::randomRationalCamera(size, size, 0.2), size, size);
    const std::vector<Eigen::Matrix3d>& q = map.stage(0);
    double worst = 0.0;
    for (int y : {0, 1999, 3999}) {
      for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
        RowQuadratics row(q, y, x0);
        for (int i = 0; i < kSpanPixels; ++i, row.advance()) {
          Eigen::Vector2d incremental;
          if (!row.current(incremental)) continue;
          const Eigen::Vector3d x(x0 + i + 0.5, y + 0.5, 1.0);
          const Eigen::Vector2d direct(x.dot(q[0] * x) / x.dot(q[2] * x), x.dot(q[1] * x) / x.dot(q[2] * x));
          worst = std::max(worst, (incremental - direct).norm());
        }
      }
    }
    qInfo("forward-difference drift over 6000 px rows, re-anchored every %d px: %.3g px", kSpanPixels, worst);
    QVERIFY2(worst < 1e-6, qPrintable(QString("drift %1 px").arg(worst)));
  }

  // The batch form the cell certification uses (RationalMap::evaluateBatch) gives what
  // evaluate() gives point by point (value, Jacobian, denominator's sign), to rounding; a
  // chain has no batch form.
  void batchEvaluationAgreesWithPointwise() {
    const FrameSize size{6000, 4000};
    test::rng().seed(23);
    const RationalMap map(test::randomRationalCamera(size, size, 0.3), size, size);
    double u[RationalMap::kBatch], v[RationalMap::kBatch];
    std::uniform_real_distribution<double> along(-500.0, 6500.0);
    int compared = 0;
    for (int round = 0; round < 50; ++round) {
      for (int k = 0; k < RationalMap::kBatch; ++k) u[k] = along(test::rng()), v[k] = along(test::rng());
      RationalMap::Batch b;
      QVERIFY(map.evaluateBatch(u, v, b));
      for (int k = 0; k < RationalMap::kBatch; ++k) {
        Eigen::Vector2d f;
        Eigen::Matrix2d j;
        unsigned signs = 0;
        if (!map.evaluate(Eigen::Vector2d(u[k], v[k]), f, &j, &signs)) continue;
        const double scale = 1.0 + f.norm();
        QVERIFY(std::abs(b.x[k] - f.x()) <= 1e-12 * scale && std::abs(b.y[k] - f.y()) <= 1e-12 * scale);
        const double jscale = 1.0 + j.cwiseAbs().maxCoeff();
        QVERIFY(std::abs(b.j00[k] - j(0, 0)) <= 1e-12 * jscale && std::abs(b.j01[k] - j(0, 1)) <= 1e-12 * jscale);
        QVERIFY(std::abs(b.j10[k] - j(1, 0)) <= 1e-12 * jscale && std::abs(b.j11[k] - j(1, 1)) <= 1e-12 * jscale);
        QCOMPARE(b.den[k] < 0.0, signs != 0u);
        ++compared;
      }
    }
    QVERIFY(compared > 500);
    Camera chain = test::randomRationalCamera(size, size, 0.1);
    chain.stages().push_back(chain.stages().front());
    RationalMap::Batch unused;
    QVERIFY(!RationalMap(chain, size, size).evaluateBatch(u, v, unused));
  }

  // The Jacobian's derivative along a direction (the cells' cross derivatives) against a
  // central difference of evaluate()'s Jacobian, whose error ~h² |∂³F| is far below the
  // tolerance at h = 1e-3 px; a chain has no analytic form.
  void jacobianDerivativeAgreesWithDifferences() {
    const FrameSize size{6000, 4000};
    test::rng().seed(29);
    const RationalMap map(test::randomRationalCamera(size, size, 0.3), size, size);
    std::uniform_real_distribution<double> along(-500.0, 6500.0), turn(-1.0, 1.0);
    constexpr double h = 1e-3;
    int compared = 0;
    for (int k = 0; k < 400; ++k) {
      const Eigen::Vector2d s(along(test::rng()), along(test::rng()));
      const Eigen::Vector2d w(turn(test::rng()), turn(test::rng()));
      Eigen::Matrix2d analytic, jp, jm;
      Eigen::Vector2d f;
      if (!map.evaluate(s + h * w, f, &jp) || !map.evaluate(s - h * w, f, &jm)) continue;
      QVERIFY(map.jacobianDerivative(s, w, analytic));
      const Eigen::Matrix2d differenced = (jp - jm) / (2.0 * h);
      const double scale = 1e-6 * (1.0 + differenced.cwiseAbs().maxCoeff());
      QVERIFY2((analytic - differenced).cwiseAbs().maxCoeff() <= scale,
               qPrintable(QString("at %1,%2: off by %3").arg(s.x()).arg(s.y())
                              .arg((analytic - differenced).cwiseAbs().maxCoeff())));
      ++compared;
    }
    QVERIFY(compared > 300);
    Camera chain = test::randomRationalCamera(size, size, 0.1);
    chain.stages().push_back(chain.stages().front());
    Eigen::Matrix2d unused;
    QVERIFY(!RationalMap(chain, size, size).jacobianDerivative({100, 100}, {1, 0}, unused));
  }

  void kernelsAgreeWithExactReference_data() {
    QTest::addColumn<Camera>("camera");
    QTest::addColumn<bool>("force_rational");
    const FrameSize size{400, 300};
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t(0, 2) = 0.13;
    Eigen::Matrix3d a = t;
    a(0, 0) = 1.1;
    a(0, 1) = 0.2;
    a(1, 0) = -0.15;
    Eigen::Matrix3d h = a;
    h(2, 0) = 0.12;
    h(2, 1) = -0.08;
    Eigen::Matrix3d horizon = Eigen::Matrix3d::Identity();
    horizon(2, 0) = 1.5;
    for (bool force : {false, true}) {
      const char* tag = force ? " as rational" : "";
      QTest::newRow(qPrintable(QString("identity%1").arg(tag)))
          << Camera::identity({Block{BlockKind::Position, 3}}, size, size) << force;
      QTest::newRow(qPrintable(QString("translation%1").arg(tag))) << test::homographyCamera(t, size, size) << force;
      QTest::newRow(qPrintable(QString("affine%1").arg(tag))) << test::homographyCamera(a, size, size) << force;
      QTest::newRow(qPrintable(QString("homography%1").arg(tag))) << test::homographyCamera(h, size, size) << force;
      QTest::newRow(qPrintable(QString("horizon in frame%1").arg(tag)))
          << test::homographyCamera(horizon, size, size) << force;
    }
    test::rng().seed(7);
    for (double strength : {0.05, 0.1, 0.2})
      QTest::newRow(qPrintable(QString("random rational %1").arg(strength)))
          << test::randomRationalCamera(size, size, strength) << false;
    Eigen::Matrix3d q2 = Eigen::Matrix3d::Zero();
    q2(0, 0) = -2.0;
    q2(2, 2) = 1.0;
    QTest::newRow("pole through frame") << Camera::rtcam({sym(0, 2), sym(1, 2), q2}, size, size) << false;
  }

  void kernelsAgreeWithExactReference() {
    QFETCH(Camera, camera);
    QFETCH(bool, force_rational);
    const Agreement a = compareWithReference(camera, camera.sourceSize(), camera.targetSize(), force_rational);
    QVERIFY(a.compared > 0);
    QVERIFY2(a.max_px <= 1.0 / 256.0, qPrintable(QString("max %1 px").arg(a.max_px)));
    QCOMPARE(a.validity_mismatch, 0LL);
  }

  // The seed (fitted inverse + grid correction) passes its one-evaluation check almost
  // everywhere: Newton is the exception, not the rule.
  void seedCheckLeavesNewtonRare() {
    const FrameSize size{600, 400};
    test::rng().seed(5);
    const Camera camera = test::randomRationalCamera(size, size, 0.1);
    const ImageF src = test::syntheticImage(size.width, size.height);
    WarpSummary s;
    const ImageF out = warpImage(src, camera, {}, &s);
    QCOMPARE(s.kernel, std::string("rational"));
    const double share = static_cast<double>(s.newton_pixels) / (size.width * size.height);
    qInfo("pixels needing Newton: %lld (%.4f%%)", s.newton_pixels, 100.0 * share);
    QVERIFY2(share < 0.01, qPrintable(QString("%1 of pixels ran Newton").arg(share)));
  }

  // The SIMD clone picked at run time and the portable scalar code give the same image, bit
  // for bit, and the same summary, on a strong random map: the checked path (neither
  // contracts to FMA) and the certified cells' patches (fused multiply-adds in both, each
  // rounded once whatever the width, in the same order). Homographies' float spans are
  // compared within tolerance instead (test_fast_paths, floatSpans…).
  void dispatchedAndScalarAgree() {
    const FrameSize size{300, 200};
    test::rng().seed(13);
    const Camera camera = test::randomRationalCamera(size, size, 0.15);
    const ImageF src = test::syntheticImage(size.width, size.height);
    WarpOptions o;
    WarpSummary dispatched_summary, scalar_summary;
    const ImageF dispatched = warpImage(src, camera, o, &dispatched_summary);
    o.coordinates.scalar_only = true;
    const ImageF scalar = warpImage(src, camera, o, &scalar_summary);
    QCOMPARE(dispatched_summary.certified_share, scalar_summary.certified_share);
    QVERIFY(dispatched_summary.certified_share < 1.0);  // the checked path ran too
    QVERIFY(dispatched.data == scalar.data);
    QCOMPARE(dispatched_summary.newton_pixels, scalar_summary.newton_pixels);
    QCOMPARE(dispatched_summary.transparent_pixels, scalar_summary.transparent_pixels);
  }

  // 8-bit and 16-bit sources read in place give the float path's result, rounded.
  void pixelFormatsAgreeWithFloat_data() {
    QTest::addColumn<int>("type");
    QTest::addColumn<int>("channels");
    QTest::addColumn<bool>("append_alpha");
    for (int type : {0, 1, 2})
      for (int c = 1; c <= 4; ++c)
        for (bool append : {false, true}) {
          if (append && c == 4) continue;  // a source with alpha keeps its own: nothing to append
          QTest::newRow(qPrintable(QString("type %1, %2 channels%3").arg(type).arg(c).arg(append ? ", +alpha" : "")))
              << type << c << append;
        }
  }

  void pixelFormatsAgreeWithFloat() {
    QFETCH(int, type);
    QFETCH(int, channels);
    QFETCH(bool, append_alpha);
    const PixelType pt = type == 0 ? PixelType::UInt8 : type == 1 ? PixelType::UInt16 : PixelType::Float;
    const float full = pixelTypeFullScale(pt);
    const FrameSize size{130, 90};
    // Source values already on the type's scale, so the float path is the exact answer.
    const ImageF unit = test::syntheticImage(size.width, size.height, channels);
    const int alpha = channels == 4 ? 3 : -1;
    // The reference treats alpha as a plain channel (no clamp to the float scale's 1).
    ImageF scaled(size.width, size.height, channels, -1);
    std::vector<std::uint8_t> u8(unit.data.size());
    std::vector<std::uint16_t> u16(unit.data.size());
    for (size_t i = 0; i < unit.data.size(); ++i) {
      const float v = std::round(unit.data[i] * full);
      scaled.data[i] = pt == PixelType::Float ? unit.data[i] : v;
      u8[i] = static_cast<std::uint8_t>(std::min(v, 255.0f));
      u16[i] = static_cast<std::uint16_t>(v);
    }
    const void* raw = pt == PixelType::UInt8 ? static_cast<const void*>(u8.data())
                      : pt == PixelType::UInt16 ? static_cast<const void*>(u16.data())
                                                : static_cast<const void*>(scaled.data.data());
    test::rng().seed(9);
    const Camera camera = test::randomRationalCamera(size, size, 0.1);
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      o.threads = 2;
      const ImageF want = warpImage(scaled, camera, o);  // alpha appended as coverage in [0, 1]
      const int oc = channels + (append_alpha ? 1 : 0);
      std::vector<unsigned char> bytes(static_cast<size_t>(size.width) * size.height * oc * pixelTypeSize(pt));
      ImageView out = packedView<void>(bytes.data(), size.width, size.height, oc, pt, append_alpha ? channels : alpha);
      WarpSummary s;
      warpImage(packedView<const void>(raw, size.width, size.height, channels, pt, alpha), camera, out, o, &s);
      double worst = 0.0;
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
          for (int c = 0; c < oc; ++c) {
            const size_t k = (static_cast<size_t>(y) * size.width + x) * oc + c;
            const double got = pt == PixelType::UInt8    ? bytes[k]
                               : pt == PixelType::UInt16 ? reinterpret_cast<const std::uint16_t*>(bytes.data())[k]
                                                         : reinterpret_cast<const float*>(bytes.data())[k];
            double expected = want.pixel(x, y)[c];
            if (c == channels) expected *= full;  // appended coverage on the type's scale
            if (c == alpha || pt != PixelType::Float)
              expected = std::clamp(expected, 0.0, static_cast<double>(full));
            worst = std::max(worst, std::abs(got - expected));
          }
      // Integers round to nearest (0.5) plus float accumulation on a 65535 scale; 8-bit
      // bilinear runs in fixed point (1/255 and 1/256 weights): within one code value.
      const double allowed = pt == PixelType::Float ? 1e-5 : pt == PixelType::UInt8 ? 1.0 : 0.5 + 1e-5 * full;
      QVERIFY2(worst <= allowed, qPrintable(QString("%1: worst %2").arg(filterName(f).data()).arg(worst)));
    }
  }

  // The span sampler against sampling.h's reference Sampler at random points, borders and
  // beyond included, for every filter and channel count (float: the same arithmetic).
  void spanSamplerAgreesWithReferenceSampler() {
    const FrameSize size{37, 23};
    test::rng().seed(17);
    for (int channels = 1; channels <= 4; ++channels) {
      const ImageF src = test::syntheticImage(size.width, size.height, channels);
      for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
        const Sampler reference(src, f);
        ImageF out(kSpanPixels, 1, reference.outputChannels(), reference.outputAlpha());
        const SpanSampler sampler(viewOf(src), viewOf(out), f);
        float sx[kSpanPixels], sy[kSpanPixels];
        unsigned char valid[kSpanPixels];
        for (int i = 0; i < kSpanPixels; ++i) {
          sx[i] = static_cast<float>(test::uniform(-3.0, size.width + 3.0));
          sy[i] = static_cast<float>(test::uniform(-3.0, size.height + 3.0));
          valid[i] = i % 7 != 3;
        }
        sampler.run(0, 0, kSpanPixels, sx, sy, valid);
        for (int i = 0; i < kSpanPixels; ++i) {
          float want[5] = {0, 0, 0, 0, 0};
          if (valid[i]) reference.sample(sx[i], sy[i], want);
          for (int c = 0; c < out.channels; ++c)
            QVERIFY2(std::abs(out.pixel(i, 0)[c] - want[c]) < 1e-5,
                     qPrintable(QString("%1 ch %2, point %3: %4 vs %5").arg(filterName(f).data()).arg(channels)
                                    .arg(i).arg(out.pixel(i, 0)[c]).arg(want[c])));
        }
      }
    }
  }

  void wholePixelTranslationCopies() {
    const FrameSize size{160, 120};
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t(0, 2) = 3.0 / 80.0;  // 3 px right, 2 px up in a frame of scale 80 px
    t(1, 2) = -2.0 / 80.0;
    const Camera camera = test::homographyCamera(t, size, size);
    const ImageF src = test::syntheticImage(size.width, size.height, 4);
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      WarpSummary copy_summary, general_summary;
      const ImageF copy = warpImage(src, camera, o, &copy_summary);
      o.coordinates.force_rational = true;
      const ImageF general = warpImage(src, camera, o, &general_summary);
      QCOMPARE(copy_summary.kernel, std::string("translation-copy"));
      double worst = 0.0;
      for (size_t i = 0; i < copy.data.size(); ++i)
        worst = std::max(worst, static_cast<double>(std::abs(copy.data[i] - general.data[i])));
      QVERIFY2(worst < 1e-4, qPrintable(QString("worst %1").arg(worst)));
      QCOMPARE(copy_summary.transparent_pixels, general_summary.transparent_pixels);
    }
    // The copied rows sit where the map says: output (x, y) shows source (x − 3, y + 2).
    const ImageF copy = warpImage(src, camera);
    QCOMPARE(copy.pixel(10, 10)[0], src.pixel(7, 12)[0]);
  }

  // A one-pixel checkerboard shown at a quarter of its size: one tap per pixel aliases to
  // values near 0 or 1, supersampling the footprint averages to ½.
  void antialiasAveragesMinifiedPattern() {
    const FrameSize size{400, 400};
    ImageF checker(size.width, size.height, 1);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) checker.pixel(x, y)[0] = (x + y) % 2 ? 1.0f : 0.0f;
    const Camera camera = Camera::identity({Block{BlockKind::Position, 3}}, size, {100, 100});
    WarpOptions o;
    o.filter = Filter::Nearest;
    const ImageF aliased = warpImage(checker, camera, o);
    o.antialias = true;
    const ImageF smooth = warpImage(checker, camera, o);
    double aliased_dev = 0.0, smooth_dev = 0.0;
    for (int y = 10; y < 90; ++y)
      for (int x = 10; x < 90; ++x) {
        aliased_dev = std::max(aliased_dev, std::abs(aliased.pixel(x, y)[0] - 0.5));
        smooth_dev = std::max(smooth_dev, std::abs(smooth.pixel(x, y)[0] - 0.5));
      }
    QVERIFY2(aliased_dev > 0.4, qPrintable(QString("aliased %1").arg(aliased_dev)));
    QVERIFY2(smooth_dev < 0.05, qPrintable(QString("smooth %1").arg(smooth_dev)));
  }

  void mipPyramidPicksMatchingLevel() {
    const FrameSize size{640, 480};
    const MipPyramid pyramid(test::syntheticImage(size.width, size.height));
    QCOMPARE(pyramid.level(1).width, 320);
    QCOMPARE(pyramid.levelFor(1.0), 0);
    QCOMPARE(pyramid.levelFor(4.5), 2);
    // A 160×120 preview of the photo: one output pixel covers 4 source pixels, level 2.
    const Camera camera = Camera::identity({Block{BlockKind::Position, 3}}, size, size);
    WarpOptions o;
    o.width = 160;
    WarpSummary s;
    const ImageF preview = warpPreview(pyramid, camera, o, &s);
    QCOMPARE(preview.width, 160);
    QVERIFY2(s.note.rfind("mip level 2", 0) == 0, s.note.c_str());
    // The preview is the 4×4 box average of the photo, which level 2 holds exactly.
    QVERIFY(std::abs(preview.pixel(40, 30)[1] - pyramid.level(2).pixel(40, 30)[1]) < 1e-5);
  }
};

QTEST_GUILESS_MAIN(TestFused)
#include "test_fused.moc"
