// SPDX-License-Identifier: Apache-2.0
// The kernel ladder (the cheapest exact kernel per camera class): every exact kernel agrees
// with the general rational path on the same camera; poles and folds give transparency, never
// NaN, and the right sheet of the map where there is a choice (checked against closed forms).
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <optional>

using namespace artcam;

namespace {

const FrameSize kSize{160, 120};

double maxAbsDiff(const ImageF& a, const ImageF& b) {
  if (a.data.size() != b.data.size()) return 1e30;
  double m = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i)
    m = std::max(m, static_cast<double>(std::abs(a.data[i] - b.data[i])));
  return m;
}

bool allFinite(const ImageF& img) {
  for (float v : img.data)
    if (!std::isfinite(v)) return false;
  return true;
}

// A position camera whose three tensors are given in the normalised frames.
Camera rationalCamera(const Eigen::Matrix3d& q0, const Eigen::Matrix3d& q1, const Eigen::Matrix3d& q2) {
  return Camera::rtcam({q0, q1, q2}, kSize, kSize);
}

Eigen::Matrix3d sym(int a, int b) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(a, b) += 0.5;
  m(b, a) += 0.5;
  return m;
}

// Checks every output pixel against a closed-form inverse (target pixel → source pixel or none).
template <class Inverse>
void checkAgainstClosedForm(const ImageF& source, const ImageF& out, Inverse inverse,
                            long long* expected_transparent) {
  double max_diff = 0.0;
  long long none = 0;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const std::optional<Eigen::Vector2d> s = inverse(Eigen::Vector2d(x + 0.5, y + 0.5));
      float want[4] = {0, 0, 0, 0};
      if (s) want[3] = static_cast<float>(test::referenceBilinear(source, s->x(), s->y(), want));
      else ++none;
      const float* got = out.pixel(x, y);
      for (int c = 0; c < 4; ++c) max_diff = std::max(max_diff, static_cast<double>(std::abs(got[c] - want[c])));
    }
  *expected_transparent = none;
  QVERIFY2(max_diff < 1e-4, qPrintable(QString("max diff %1").arg(max_diff)));
}

}  // namespace

class TestKernels : public QObject {
  Q_OBJECT

 private slots:
  void exactKernelsAgreeWithRational_data() {
    QTest::addColumn<int>("out_w");
    QTest::addColumn<Eigen::Matrix3d>("h");
    QTest::addColumn<QString>("kernel");
    QTest::addColumn<long long>("nearest_ties");  // values allowed to differ, see below
    Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
    QTest::newRow("identity") << 160 << id << "identity" << 0LL;
    QTest::newRow("identity to another size") << 200 << id << "affine" << 200LL * 150 * 4 / 4;
    Eigen::Matrix3d t = id;
    t(0, 2) = 0.13;
    t(1, 2) = -0.07;
    QTest::newRow("translation") << 160 << t << "translation" << 8LL;
    Eigen::Matrix3d a = t;
    a(0, 0) = 1.1;
    a(0, 1) = 0.2;
    a(1, 0) = -0.15;
    a(1, 1) = 0.9;
    QTest::newRow("affine") << 160 << a << "affine" << 8LL;
    Eigen::Matrix3d h = a;
    h(2, 0) = 0.12;
    h(2, 1) = -0.08;
    // The rational kernel's patch (inverse_cells.h) is exact to ~1e-6 px in float, so a few
    // more exact ties of the 1.25 scale round the other way than the inverse homography's.
    QTest::newRow("homography") << 160 << h << "homography" << 16LL;
    // The horizon u_n = −1/1.5 crosses the frame: beyond it the map has no preimage.
    Eigen::Matrix3d horizon = id;
    horizon(2, 0) = 1.5;
    QTest::newRow("homography with horizon in frame") << 160 << horizon << "homography" << 160LL;
  }

  void exactKernelsAgreeWithRational() {
    QFETCH(int, out_w);
    QFETCH(Eigen::Matrix3d, h);
    QFETCH(QString, kernel);
    QFETCH(long long, nearest_ties);
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    const Camera camera = test::homographyCamera(h, kSize, kSize);
    for (Filter filter : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions options;
      options.filter = filter;
      options.width = out_w;
      WarpSummary exact_summary, general_summary;
      const ImageF exact = warpImage(src, camera, options, &exact_summary);
      options.coordinates.force_rational = true;
      const ImageF general = warpImage(src, camera, options, &general_summary);
      QCOMPARE(QString::fromStdString(exact_summary.kernel), kernel);
      QCOMPARE(general_summary.kernel, std::string("rational"));
      QVERIFY(allFinite(exact) && allFinite(general));
      // Nearest flips where a source point lands exactly on a pixel edge (an exact tie, e.g. every
      // fifth column at a 1.25 scale): the two kernels round it either way within 1e-7 px.
      const double diff = maxAbsDiff(exact, general);
      if (filter == Filter::Nearest) {
        long long differing = 0;  // values
        for (size_t i = 0; i < exact.data.size(); ++i) differing += exact.data[i] != general.data[i];
        QVERIFY2(differing <= nearest_ties, qPrintable(QString("%1 values differ").arg(differing)));
      } else {
        // Both round positions to float and the rational kernel's patch is certified to
        // 1/4096 px: 3e-4 in value is ~3e-4 px at this image's steepest gradient (1 per px),
        // a tenth of the 1/256 px position budget.
        QVERIFY2(diff < 3e-4, qPrintable(QString("%1: max diff %2").arg(filterName(filter).data()).arg(diff)));
      }
      QCOMPARE(exact_summary.transparent_pixels, general_summary.transparent_pixels);
    }
  }

  // y = (u, v) / (1 − 2u²): the pole curve u = ±1/√2 crosses the source frame. Only the sheet
  // |u| < 1/√2 (the centre's denominator sign) is rendered, where u solves 2 y_u u² + u − y_u = 0.
  void poleThroughFrameRendersCentreSheet() {
    Eigen::Matrix3d q2 = Eigen::Matrix3d::Zero();
    q2(0, 0) = -2.0;
    q2(2, 2) = 1.0;
    const Camera camera = rationalCamera(sym(0, 2), sym(1, 2), q2);
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    WarpSummary summary;
    const ImageF out = warpImage(src, camera, {}, &summary);
    QCOMPARE(summary.kernel, std::string("rational"));
    QVERIFY(allFinite(out));
    long long expected_transparent = 0;
    checkAgainstClosedForm(src, out, [&](const Eigen::Vector2d& t) -> std::optional<Eigen::Vector2d> {
      const Eigen::Vector2d y = normalizedFromPixel(kSize, t);
      const double u = std::abs(y.x()) < 1e-12 ? 0.0 : (-1.0 + std::sqrt(1.0 + 8.0 * y.x() * y.x())) / (4.0 * y.x());
      return pixelFromNormalized(kSize, Eigen::Vector2d(u, y.y() * (1.0 - 2.0 * u * u)));
    }, &expected_transparent);
    for (Filter f : {Filter::Nearest, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      QVERIFY(allFinite(warpImage(src, camera, o)));
    }
  }

  // y_u = u + u²: the map folds at u = −1/2. Targets y_u < −1/4 have no preimage (transparent);
  // the others take the centre's fold, u = (−1 + √(1 + 4 y_u)) / 2.
  void foldedMapKeepsCentreFold() {
    Eigen::Matrix3d q0 = sym(0, 2);
    q0(0, 0) = 1.0;
    Eigen::Matrix3d q2 = Eigen::Matrix3d::Zero();
    q2(2, 2) = 1.0;
    const Camera camera = rationalCamera(q0, sym(1, 2), q2);
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    WarpSummary summary;
    const ImageF out = warpImage(src, camera, {}, &summary);
    QVERIFY(allFinite(out));
    long long expected_transparent = 0;
    checkAgainstClosedForm(src, out, [&](const Eigen::Vector2d& t) -> std::optional<Eigen::Vector2d> {
      const Eigen::Vector2d y = normalizedFromPixel(kSize, t);
      const double disc = 1.0 + 4.0 * y.x();
      if (disc < 0.0) return std::nullopt;
      return pixelFromNormalized(kSize, Eigen::Vector2d((-1.0 + std::sqrt(disc)) / 2.0, y.y()));
    }, &expected_transparent);
    QVERIFY(expected_transparent > 0);
    QCOMPARE(summary.transparent_pixels, expected_transparent);
  }

  // A pole through the very centre, where the sign reference itself is undefined: no NaN.
  void poleThroughCentreNeverNaN() {
    const Camera camera = rationalCamera(sym(0, 2), sym(1, 2), sym(0, 2));  // y = (1, v / u)
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      WarpOptions o;
      o.filter = f;
      WarpSummary summary;
      const ImageF out = warpImage(src, camera, o, &summary);
      QVERIFY(allFinite(out));
      for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
          if (out.pixel(x, y)[3] == 0.0f)
            for (int c = 0; c < 3; ++c) QCOMPARE(out.pixel(x, y)[c], 0.0f);
    }
  }

  void randomRationalThreadsAgree() {
    test::rng().seed(11);
    const Camera camera = test::randomRationalCamera(kSize, kSize, 0.2);
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    WarpOptions o;
    o.threads = 1;
    const ImageF one = warpImage(src, camera, o);
    o.threads = 3;
    const ImageF three = warpImage(src, camera, o);
    QVERIFY(one.data == three.data);
    QVERIFY(allFinite(one));
  }

  void sourceAlphaIsKept() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height, 4);
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(0, 2) = 0.05;
    const ImageF out = warpImage(src, test::homographyCamera(h, kSize, kSize));
    QCOMPARE(out.channels, 4);
    QCOMPARE(out.alpha_channel, 3);
    // Interior alpha is the interpolated source alpha, not a coverage of 1.
    QVERIFY(out.pixel(80, 60)[3] < 0.96f && out.pixel(80, 60)[3] > 0.5f);
  }

  void outputSizeFollowsOptions() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    const Camera camera = Camera::identity({Block{BlockKind::Position, 3}}, kSize, {320, 240});
    QCOMPARE(warpImage(src, camera).width, 320);
    WarpOptions o;
    o.width = 80;
    const ImageF half = warpImage(src, camera, o);
    QCOMPARE(half.width, 80);
    QCOMPARE(half.height, 60);
  }

  void progressAndCancel() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    test::rng().seed(3);
    const Camera camera = test::randomRationalCamera(kSize, kSize, 0.1);
    std::vector<double> seen;
    WarpOptions o;
    o.progress = [&](double f) {
      seen.push_back(f);
      return true;
    };
    WarpSummary summary;
    QVERIFY(!warpImage(src, camera, o, &summary).empty());
    QVERIFY(!summary.cancelled);
    QVERIFY(!seen.empty());
    QVERIFY(std::is_sorted(seen.begin(), seen.end()));
    QCOMPARE(seen.back(), 1.0);

    o.progress = [](double) { return false; };
    const ImageF cancelled = warpImage(src, camera, o, &summary);
    QVERIFY(summary.cancelled);
    QVERIFY(cancelled.empty());
  }

  void refusesWhatItCannotRender() {
    const ImageF src = test::syntheticImage(kSize.width, kSize.height);
    // Paper eq 8/9: position scaled by red — geometry depends on colour, a splat job.
    const Block pos{BlockKind::Position, 3}, col{BlockKind::Colour, 4};
    Camera lens = Camera::identity({pos, col}, kSize, kSize);
    lens.stages()[0].q[0](0, 3) += 0.1;
    lens.stages()[0].q[0](3, 0) += 0.1;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, warpImage(src, lens));
    WarpOptions o;
    o.width = -1;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             warpImage(src, Camera::identity({pos}, kSize, kSize), o));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, warpImage(ImageF{}, Camera::identity({pos}, kSize, kSize)));
  }
};

QTEST_GUILESS_MAIN(TestKernels)
#include "test_kernels.moc"
