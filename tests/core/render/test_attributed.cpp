// SPDX-License-Identifier: Apache-2.0
// Attributed rendering (attributed.h, splat.h) against evaluations written here in double
// precision: closed-form colour maps, the inverse homography solved by hand, a bilinear sampler
// of the test's own, and a Newton solve of the eq 8/9 map. Splat and gather are compared on a
// geometry-only camera over the bundled photo (PSNR).
#include "core/effects/chromatic.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "core/render/splat.h"
#include "tests/core/render/photo_fixture.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <Eigen/LU>

#include <cmath>

using namespace artcam;

namespace {

constexpr int kU = 0, kV = 1, kW = 2, kR = 3, kA = 6, kN = 7;
Eigen::VectorXd e(int i, int n = kN) { return Eigen::VectorXd::Unit(n, i); }
std::vector<Block> pc() { return {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}}; }

ImageF randomRgba(int w, int h, bool with_alpha) {
  ImageF img(w, h, with_alpha ? 4 : 3, with_alpha ? 3 : -1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const float a = with_alpha ? static_cast<float>(test::uniform(0.2, 1.0)) : 1.0f;
      for (int c = 0; c < 3; ++c) p[c] = a * static_cast<float>(test::uniform(0.0, 1.0));
      if (with_alpha) p[3] = a;
    }
  return img;
}

// Test's own bilinear read of premultiplied RGBA (zero outside), at source point s in pixels.
Eigen::Vector4d bilinear(const ImageF& img, const Eigen::Vector2d& s) {
  const double fx = s.x() - 0.5, fy = s.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  Eigen::Vector4d out = Eigen::Vector4d::Zero();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int x = x0 + i, y = y0 + j;
      if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
      const double w = (i ? fx - x0 : 1 - (fx - x0)) * (j ? fy - y0 : 1 - (fy - y0));
      const float* p = img.pixel(x, y);
      Eigen::Vector4d v(p[0], p[1], p[2], img.channels == 4 ? p[3] : 1.0);
      out += w * v;
    }
  return out;
}

double psnr(const ImageF& a, const ImageF& b, int margin) {
  double se = 0.0;
  long long n = 0;
  for (int y = margin; y < a.height - margin; ++y)
    for (int x = margin; x < a.width - margin; ++x) {
      if (a.pixel(x, y)[3] < 0.999f || b.pixel(x, y)[3] < 0.999f) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = a.pixel(x, y)[c] - b.pixel(x, y)[c];
        se += d * d;
        ++n;
      }
    }
  return n ? 10.0 * std::log10(1.0 / (se / static_cast<double>(n))) : 0.0;
}

}  // namespace

class TestAttributed : public QObject {
  Q_OBJECT

 private slots:
  // Identity geometry, colour transform M·c + b·a with alpha kept: every pixel from its own value.
  void colourOnlyMatchesClosedForm() {
    const FrameSize size{37, 23};
    Eigen::Matrix3d m;
    m << 0.8, 0.1, 0.05, -0.2, 1.1, 0.0, 0.05, 0.3, 0.6;
    const Eigen::Vector3d b(0.02, -0.01, 0.1);
    Camera cam = Camera::identity(pc(), size, size);
    Stage& st = cam.stages()[0];
    for (int k = 0; k < 3; ++k) {
      Eigen::VectorXd row = b[k] * e(kA);
      for (int j = 0; j < 3; ++j) row += m(k, j) * e(kR + j);
      st.q[kR + k] = symmetricOuter(row, e(kW));
    }
    const ImageF src = randomRgba(size.width, size.height, true);
    AttributedSummary summary;
    const AttributedImage out = renderAttributed(src, nullptr, cam, {}, &summary);
    QCOMPARE(summary.path, AttributedPath::ColourOnly);
    double worst = 0.0;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const float* p = src.pixel(x, y);
        const Eigen::Vector3d c(p[0], p[1], p[2]);
        const Eigen::Vector3d expected = m * c + b * p[3];  // premultiplied in, premultiplied out
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(out.colour.pixel(x, y)[k] - expected[k]));
        worst = std::max(worst, std::abs(static_cast<double>(out.colour.pixel(x, y)[3]) - p[3]));
      }
    QVERIFY2(worst < 1e-5, qPrintable(QString("max error %1").arg(worst)));
  }

  // Homography geometry with a position-dependent colour (colour × (1 − k·u) of the SOURCE
  // position, a pc part feeding colour): gathered through the inverse solved here.
  void gatherMatchesHandInverse() {
    const FrameSize src_size{41, 29}, out_size{47, 31};
    Eigen::Matrix3d h;
    h << 1.1, 0.08, 0.03, -0.05, 0.95, -0.04, 0.06, -0.03, 1.0;
    const double k = 0.4;
    Stage st;
    st.q.assign(kN, Eigen::MatrixXd::Zero(kN, kN));
    for (int i = 0; i < 3; ++i) {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(kN);
      row.head<3>() = h.row(i).transpose();
      st.q[i] = symmetricOuter(e(kW), row);
    }
    for (int c = 0; c < 3; ++c) st.q[kR + c] = symmetricOuter(e(kR + c), e(kW) - k * e(kU));
    st.q[kA] = symmetricOuter(e(kA), e(kW));
    const Camera cam(pc(), {st}, src_size, out_size);
    const ImageF src = randomRgba(src_size.width, src_size.height, false);
    AttributedSummary summary;
    const AttributedImage out = renderAttributed(src, nullptr, cam, {}, &summary);
    QCOMPARE(summary.path, AttributedPath::Gather);
    const Eigen::Matrix3d inv = h.inverse();
    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < out_size.height; ++y)
      for (int x = 0; x < out_size.width; ++x) {
        const Eigen::Vector2d tn = normalizedFromPixel(out_size, {x + 0.5, y + 0.5});
        const Eigen::Vector3d sh = inv * Eigen::Vector3d(tn.x(), tn.y(), 1.0);
        const Eigen::Vector2d sn = sh.head<2>() / sh.z();
        const Eigen::Vector4d c = bilinear(src, pixelFromNormalized(src_size, sn));
        Eigen::Vector4d expected = Eigen::Vector4d::Zero();
        if (c[3] > 0) {
          expected.head<3>() = c.head<3>() * (1.0 - k * sn.x());
          expected[3] = std::min(c[3], 1.0);
          // unpremultiply by the weight z_a = a, premultiply by clamp(a): the same here.
        }
        const float* p = out.colour.pixel(x, y);
        for (int ch = 0; ch < 4; ++ch) worst = std::max(worst, std::abs(p[ch] - expected[ch]));
        ++checked;
      }
    QVERIFY(checked > 1000);
    QVERIFY2(worst < 2e-4, qPrintable(QString("max error %1").arg(worst)));
  }

  // A smooth magnifying map forced through the splat on a linear-gradient image: the mesh
  // reconstruction is exact for linear data, and no interior pixel may be uncovered (cracks).
  void splatMagnifyingHasNoCracksAndIsExactOnLinearData() {
    const FrameSize src_size{40, 30}, out_size{120, 90};
    Camera cam = test::randomRationalCamera(src_size, out_size, 0.03);
    ImageF src(src_size.width, src_size.height, 3);
    const auto value = [](const Eigen::Vector2d& s, int c) { return 0.2 + 0.01 * (c + 1) * s.x() + 0.007 * s.y(); };
    for (int y = 0; y < src_size.height; ++y)
      for (int x = 0; x < src_size.width; ++x)
        for (int c = 0; c < 3; ++c) src.pixel(x, y)[c] = static_cast<float>(value({x + 0.5, y + 0.5}, c));
    AttributedOptions o;
    o.force_path = "splat";
    AttributedSummary summary;
    const AttributedImage out = renderAttributed(src, nullptr, cam, o, &summary);
    QCOMPARE(summary.path, AttributedPath::Splat);
    // Independent preimages: Newton on the model's own evaluation (Camera::evaluate).
    double worst = 0.0, worst_alpha = 0.0;
    int checked = 0;
    for (int y = 0; y < out_size.height; y += 3)
      for (int x = 0; x < out_size.width; x += 3) {
        const Eigen::Vector2d t(x + 0.5, y + 0.5);
        Eigen::Vector2d s = t * (static_cast<double>(src_size.width) / out_size.width);
        for (int it = 0; it < 30; ++it) {
          const auto f = [&](const Eigen::Vector2d& q) { return *targetPixelFromSourcePixel(cam, q); };
          Eigen::Matrix2d j;
          for (int c = 0; c < 2; ++c) {
            Eigen::Vector2d d = Eigen::Vector2d::Zero();
            d[c] = 1e-5;
            j.col(c) = (f(s + d) - f(s - d)) / 2e-5;
          }
          s -= j.inverse() * (f(s) - t);
        }
        // Only where the preimage is well inside the mesh of pixel centres.
        if (s.x() < 1.5 || s.y() < 1.5 || s.x() > src_size.width - 1.5 || s.y() > src_size.height - 1.5) continue;
        const float* p = out.colour.pixel(x, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(p[c] - value(s, c)));
        worst_alpha = std::max(worst_alpha, std::abs(1.0 - p[3]));
        ++checked;
      }
    QVERIFY(checked > 300);
    QVERIFY2(worst_alpha < 1e-5, qPrintable(QString("uncovered interior: alpha off by %1").arg(worst_alpha)));
    // Linear on each triangle of a slightly non-linear map: error ~ curvature · pixel².
    QVERIFY2(worst < 2e-4, qPrintable(QString("max error %1").arg(worst)));
  }

  // eq 8/9 on a red gradient: y = p·(1 + s·r(p)) is solved here by Newton for each output pixel.
  void colourShiftSplatMatchesNewtonSolve() {
    const FrameSize size{64, 48};
    const double s = 0.3;
    ColourShiftParams params;
    params.s = {s, 0.0, 0.0};
    const Camera red = colourShiftLayers(params, size, size)[0];
    QVERIFY(analyseStructure(red).geometry_depends_on_attributes);
    ImageF src(size.width, size.height, 3);
    const auto redAt = [&](const Eigen::Vector2d& n) { return 0.5 + 0.3 * n.x() - 0.2 * n.y(); };
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const Eigen::Vector2d n = normalizedFromPixel(size, {x + 0.5, y + 0.5});
        src.pixel(x, y)[0] = static_cast<float>(redAt(n));
        src.pixel(x, y)[1] = src.pixel(x, y)[2] = 0.9f;  // dropped by the red layer
      }
    AttributedSummary summary;
    const AttributedImage out = renderAttributed(src, nullptr, red, {}, &summary);
    QCOMPARE(summary.path, AttributedPath::Splat);
    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const Eigen::Vector2d t = normalizedFromPixel(size, {x + 0.5, y + 0.5});
        Eigen::Vector2d p = t;
        for (int it = 0; it < 50; ++it) {
          // F(p) = p·(1 + s·r(p)) − t, r linear: J = (1 + s r) I + s p ∇rᵀ.
          const double g = 1.0 + s * redAt(p);
          Eigen::Matrix2d j = g * Eigen::Matrix2d::Identity() + s * p * Eigen::RowVector2d(0.3, -0.2);
          p -= j.inverse() * (p * g - t);
        }
        const Eigen::Vector2d sp = pixelFromNormalized(size, p);
        if (sp.x() < 2 || sp.y() < 2 || sp.x() > size.width - 2 || sp.y() > size.height - 2) continue;
        const float* o = out.colour.pixel(x, y);
        worst = std::max({worst, std::abs(o[0] - redAt(p)), std::abs(static_cast<double>(o[1])),
                          std::abs(static_cast<double>(o[2])), std::abs(1.0 - o[3])});
        ++checked;
      }
    QVERIFY(checked > 1000);
    QVERIFY2(worst < 1e-3, qPrintable(QString("max error %1").arg(worst)));
  }

  // Transparent source pixels make eq 8/9's denominator p3·c4 zero: dropped, never NaN.
  void splatNeverWritesNan() {
    const FrameSize size{32, 32};
    ImageF src = randomRgba(size.width, size.height, true);
    for (int y = 8; y < 20; ++y)
      for (int x = 5; x < 30; ++x) std::fill(src.pixel(x, y), src.pixel(x, y) + 4, 0.0f);
    const AttributedImage out =
        renderLayers(src, nullptr, colourShiftLayers({{0.4, -0.3, 0.2}}, size, size));
    for (float v : out.colour.data) QVERIFY(std::isfinite(v));
  }

  // Where both apply they must agree: a rational geometry-only camera on the bundled photo.
  void splatAgreesWithGatherOnGeometry() {
    ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const FrameSize size{photo.width, photo.height};
    const Camera cam = test::randomRationalCamera(size, size, 0.04);
    const AttributedImage gathered = renderAttributed(photo, nullptr, cam);
    AttributedOptions o;
    o.force_path = "splat";
    const AttributedImage splatted = renderAttributed(photo, nullptr, cam, o);
    const double db = psnr(gathered.colour, splatted.colour, 4);
    qInfo("splat vs gather (bilinear), rational camera on coffee.png: PSNR %.2f dB", db);
    QVERIFY2(db > 38.0, qPrintable(QString("PSNR %1 dB").arg(db)));
  }

  // Minifying a one-pixel checkerboard 2.5×: the ideal (box-filtered) picture is flat 0.5. The
  // splat's sub-samples must come much closer to it than one point sample per pixel (moiré).
  void splatMinifyingDoesNotAlias() {
    const FrameSize size{240, 240};
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h(0, 0) = h(1, 1) = 0.4;
    h(0, 1) = 0.05;  // a slight shear so the grid does not line up with the output pixels
    Stage st;
    for (const Eigen::MatrixXd& q : liftHomography(h)) st.q.push_back(q);
    const Camera cam({Block{BlockKind::Position, 3}}, {st}, size, size);
    ImageF src(size.width, size.height, 3);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        for (int c = 0; c < 3; ++c) src.pixel(x, y)[c] = static_cast<float>((x + y) % 2);
    AttributedOptions o;
    o.force_path = "splat";
    const AttributedImage splatted = renderAttributed(src, nullptr, cam, o);
    o.force_path.clear();
    const AttributedImage pointwise = renderAttributed(src, nullptr, cam, o);  // gather, 1 tap
    const auto rmsFromHalf = [](const ImageF& img) {
      double se = 0.0;
      int n = 0;
      for (int y = 80; y < 160; ++y)
        for (int x = 80; x < 160; ++x) {
          const double d = img.pixel(x, y)[0] - 0.5;
          se += d * d;
          ++n;
        }
      return std::sqrt(se / n);
    };
    const double splat_rms = rmsFromHalf(splatted.colour), point_rms = rmsFromHalf(pointwise.colour);
    qInfo("1-px checkerboard minified 2.5x: RMS from flat 0.5: splat %.3f, point-sampled gather %.3f",
          splat_rms, point_rms);
    QVERIFY(splat_rms < 0.1);
    QVERIFY(splat_rms < 0.5 * point_rms);
  }

  void cancelReturnsEmpty() {
    const FrameSize size{64, 64};
    const ImageF src = randomRgba(size.width, size.height, false);
    AttributedOptions o;
    o.warp.progress = [](double) { return false; };
    AttributedSummary summary;
    const AttributedImage out = renderLayers(src, nullptr, colourShiftLayers({}, size, size), o, &summary);
    QVERIFY(summary.cancelled);
    QVERIFY(out.colour.empty());
  }

  void depthCameraWithoutDepthIsRefused() {
    const FrameSize size{8, 8};
    const Camera cam = Camera::identity(
        {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}, Block{BlockKind::Depth, 2}}, size, size);
    Camera changed = cam;
    changed.stages()[0].q[7] *= 2.0;  // depth doubles
    const ImageF src = randomRgba(8, 8, false);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, renderAttributed(src, nullptr, changed));
  }
};

QTEST_GUILESS_MAIN(TestAttributed)
#include "test_attributed.moc"
