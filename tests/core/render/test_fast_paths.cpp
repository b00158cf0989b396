// SPDX-License-Identifier: Apache-2.0
// The render's fast paths against independent answers:
// - the AVX2 8-bit samplers (nearest and bilinear: span_sampler_avx2.h; bicubic:
//   span_sampler_cubic.h) are bit-identical to the portable scalar code, borders, invalid
//   pixels and alpha included;
// - the float AVX2 coordinate spans (certified rational cells, homographies, affine maps), and
//   the AVX-512 ones of certified cells, stay within 1e-3 px of the scalar double code and
//   1/256 px of the exact inverse;
// - certified cells of the rational kernel (coordinates.h) stay within 1/256 px of the exact
//   double-precision inverse (Newton to ~1e-7 px), cover almost all of a mild lens, and none of
//   a camera whose pole runs through the frame;
// - stored-type images (core/io/stored_image.h) round-trip through a file, alpha included, and
//   an identity warp of them reproduces the file.
#include "core/effects/image_warps.h"
#include "core/io/stored_image.h"
#include "core/model/structure.h"
#include "core/mapping/coordinates.h"
#include "core/render/preview.h"
#include "core/sampling/span_sampler.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

using namespace artcam;

namespace {

// An 8-bit image with every byte varying (hash), alpha premultiplied when present.
std::vector<std::uint8_t> noiseImage(int w, int h, int channels, int alpha) {
  std::vector<std::uint8_t> img(static_cast<size_t>(w) * h * channels);
  std::uint32_t state = 12345u;
  for (size_t p = 0; p < img.size(); p += static_cast<size_t>(channels)) {
    int a = 255;
    for (int c = 0; c < channels; ++c) {
      state = state * 1664525u + 1013904223u;
      img[p + static_cast<size_t>(c)] = static_cast<std::uint8_t>(state >> 24);
    }
    if (alpha >= 0) {
      a = img[p + static_cast<size_t>(alpha)];
      if ((p / static_cast<size_t>(channels)) % 5 == 0) a = img[p + static_cast<size_t>(alpha)] = 0;
      for (int c = 0; c < channels; ++c)
        if (c != alpha) img[p + static_cast<size_t>(c)] = static_cast<std::uint8_t>(img[p + static_cast<size_t>(c)] * a / 255);
    }
  }
  return img;
}

// Rows of the warp's positions for a whole frame vs the exact reference: worst distance.
double worstAgainstReference(const Camera& camera, FrameSize size, const CoordinateOptions& co,
                             double* certified_share) {
  const CameraStructure structure = analyseStructure(camera);
  const KernelChoice choice = makeCoordinateKernel(camera, structure, size, size, co, 2);
  const auto reference = makeReferenceInverse(camera, structure, size, size);
  if (certified_share) *certified_share = choice.kernel->certifiedShare();
  std::vector<Eigen::Vector2d> exact(static_cast<size_t>(size.width));
  std::vector<unsigned char> exact_ok(static_cast<size_t>(size.width));
  float sx[kSpanPixels], sy[kSpanPixels];
  unsigned char ok[kSpanPixels];
  double worst = 0.0;
  for (int y = 0; y < size.height; ++y) {
    reference->row(y, size.width, exact.data(), exact_ok.data());
    RowState state;
    for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
      const int n = std::min(kSpanPixels, size.width - x0);
      choice.kernel->span(y, x0, n, sx, sy, ok, state);
      for (int i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(x0 + i);
        if (!ok[i] || !exact_ok[k]) continue;
        worst = std::max(worst, std::hypot(sx[i] - exact[k].x(), sy[i] - exact[k].y()));
      }
    }
  }
  return worst;
}

// The OpenCV peer's mild lens-like map (peerbench/common.hpp default_map), as in `artcam bench
// render`: n_k = p_k · (u², uv, u, v², v, 1).
Camera benchLens(FrameSize size) {
  const double p[3][6] = {{0.030, 0.020, 1.000, -0.010, 0.010, 0.005},
                          {0.010, -0.020, 0.015, 0.030, 0.980, -0.004},
                          {0.020, 0.010, 0.040, -0.020, -0.030, 1.000}};
  std::vector<Eigen::Matrix3d> q(3);
  for (int k = 0; k < 3; ++k)
    q[static_cast<size_t>(k)] << p[k][0], p[k][1] / 2, p[k][2] / 2, p[k][1] / 2, p[k][3],
        p[k][4] / 2, p[k][2] / 2, p[k][4] / 2, p[k][5];
  return Camera::rtcam(q, size, size);
}

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("artcam-fast-paths-" + std::to_string(QCoreApplication::applicationPid()) + "-" + name);
}

}  // namespace

class TestFastPaths : public QObject {
  Q_OBJECT

 private slots:
  void simdSamplerMatchesScalar_data() {
    QTest::addColumn<int>("channels");
    QTest::addColumn<int>("alpha");
    QTest::addColumn<int>("filter");
    for (int f : {0, 1, 2})
      for (int c : {3, 4})
        for (int a : {-1, c - 1, c}) {
          if (c == 3 && a == 2) continue;  // RGB with alpha is not a layout we store
          if (c == 4 && a == 4) continue;  // a = c: alpha appended to RGB (previews)
          const char* name = f == 0 ? "nearest" : f == 1 ? "bilinear" : "bicubic";
          QTest::newRow(qPrintable(QString("%1 %2ch alpha %3").arg(name).arg(c).arg(a))) << c << a << f;
        }
  }

  void simdSamplerMatchesScalar() {
    QFETCH(int, channels);
    QFETCH(int, alpha);
    QFETCH(int, filter);
    const Filter f = filter == 0 ? Filter::Nearest : filter == 1 ? Filter::Bilinear : Filter::Bicubic;
    const int w = 53, h = 29;  // odd sizes: the last row and column are borders
    const bool append = alpha == channels;  // alpha appended to the output only
    const int src_alpha = append ? -1 : alpha, out_channels = channels + (append ? 1 : 0);
    const std::vector<std::uint8_t> img = noiseImage(w, h, channels, src_alpha);
    const ConstImageView src = packedView<const void>(img.data(), w, h, channels, PixelType::UInt8, src_alpha);
    const int n = 61;  // not a multiple of 8: a scalar tail
    std::vector<std::uint8_t> a(static_cast<size_t>(n) * out_channels), b(a.size());
    const ImageView out_a = packedView<void>(a.data(), n, 1, out_channels, PixelType::UInt8, alpha);
    const ImageView out_b = packedView<void>(b.data(), n, 1, out_channels, PixelType::UInt8, alpha);
    const SpanSampler simd(src, out_a, f, true), scalar(src, out_b, f, false);
    QVERIFY(!scalar.usesSimd());
    qInfo("AVX2 sampler in use: %s", simd.usesSimd() ? "yes" : "no (this CPU has no AVX2)");
    test::rng().seed(23);
    float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    for (int round = 0; round < 400; ++round) {
      // Mostly interior groups (the vector path), some straddling or beyond the borders.
      const double margin = round % 4 == 0 ? 3.0 : -1.0;
      for (int i = 0; i < n; ++i) {
        sx[i] = static_cast<float>(test::uniform(-margin, w + margin));
        sy[i] = static_cast<float>(test::uniform(-margin, h + margin));
        valid[i] = (round % 3 == 0 && i % 11 == 5) ? 0 : 1;
      }
      if (round == 1) {  // the extreme interior corners, exactly
        sx[0] = 0.5f, sy[0] = 0.5f, sx[1] = w - 0.5001f, sy[1] = h - 0.5001f;
        sx[2] = w - 1.5f, sy[2] = h - 1.5f;
      }
      const long long ta = simd.run(0, 0, n, sx, sy, valid), tb = scalar.run(0, 0, n, sx, sy, valid);
      QCOMPARE(ta, tb);
      QVERIFY2(a == b, qPrintable(QString("round %1 differs").arg(round)));
    }
  }

  // A mild lens: nearly every cell certified, and the unchecked positions still within budget
  // of the exact inverse (with certification off, the checked path: the same budget).
  void certifiedCellsStayWithinBudget() {
    // The OpenCV peer's mild lens-like map (peerbench/common.hpp default_map, as in `artcam
    // bench render`), on a frame large enough for 32-px cells to be smooth at 1/512 px.
    const FrameSize size{2000, 1500};
    const Camera camera = benchLens(size);
    CoordinateOptions co;
    double share = 0.0;
    const double worst = worstAgainstReference(camera, size, co, &share);
    qInfo("certified share %.3f, worst %.2e px", share, worst);
    QVERIFY2(share > 0.6, qPrintable(QString("certified share %1").arg(share)));
    QVERIFY2(worst <= 1.0 / 256.0, qPrintable(QString("worst %1 px").arg(worst)));
    co.certify_tolerance_px = 0.0;
    double none = 1.0;
    const double checked = worstAgainstReference(camera, size, co, &none);
    QCOMPARE(none, 0.0);
    QVERIFY2(checked <= 1.0 / 256.0, qPrintable(QString("checked worst %1 px").arg(checked)));
  }

  // The SIMD coordinate spans run in float, re-anchored at each span's first pixel (certified
  // cells of the rational kernel, homographies without a horizon in the span): every position
  // within 1/256 px of the exact double inverse and within 1e-3 px of the scalar double code,
  // with the same preimage flags. Cameras: the bench's mild lens (all cells certified), a
  // strong barrel whose fold circle cuts the frame's corners (refined cells), a strong
  // perspective whose horizon crosses the frame (spans at the horizon take the double path),
  // a milder one, and an affine map (W = 1).
  void floatSpansAgreeWithScalarAndReference_data() {
    QTest::addColumn<Camera>("camera");
    QTest::addColumn<bool>("avx512");
    const FrameSize size{1200, 800};
    QTest::newRow("mild lens") << benchLens(size) << true;
    QTest::newRow("mild lens, AVX2 lanes") << benchLens(size) << false;
    // Open cells split into certified squares (float patches) and the per-pixel path, in runs
    // that start and end inside cells.
    QTest::newRow("strong barrel") << radialLensCamera(-0.6, size) << true;
    Eigen::Matrix3d h;
    h << 1.1, 0.2, 0.05, -0.1, 0.9, 0.02, 0.4, 0.9, 1.0;  // horizon 0.4 x + 0.9 y + 1 = 0 crosses
    QTest::newRow("perspective with horizon") << test::homographyCamera(h, size, size) << true;
    h << 1.3, 0.1, 0.02, -0.05, 0.8, -0.03, 0.05, -0.08, 1.0;
    QTest::newRow("perspective") << test::homographyCamera(h, size, size) << true;
    h << 1.02, 0.05, 0.01, -0.04, 0.99, -0.02, 0.0, 0.0, 1.0;
    QTest::newRow("affine") << test::homographyCamera(h, size, size) << true;
  }

  void floatSpansAgreeWithScalarAndReference() {
    QFETCH(Camera, camera);
    QFETCH(bool, avx512);
    const FrameSize size{1200, 800};
    const CameraStructure structure = analyseStructure(camera);
    CoordinateOptions simd_options, scalar_options;
    simd_options.allow_avx512 = avx512;
    scalar_options.scalar_only = true;
    const KernelChoice simd = makeCoordinateKernel(camera, structure, size, size, simd_options, 2);
    const KernelChoice scalar = makeCoordinateKernel(camera, structure, size, size, scalar_options, 2);
    const auto reference = makeReferenceInverse(camera, structure, size, size);
    std::vector<Eigen::Vector2d> exact(static_cast<size_t>(size.width));
    std::vector<unsigned char> exact_ok(static_cast<size_t>(size.width));
    float ax[kSpanPixels], ay[kSpanPixels], bx[kSpanPixels], by[kSpanPixels];
    unsigned char a_ok[kSpanPixels], b_ok[kSpanPixels];
    double to_scalar = 0.0, to_exact = 0.0;
    long long compared = 0, flags_differ = 0;
    for (int y = 0; y < size.height; y += 3) {
      reference->row(y, size.width, exact.data(), exact_ok.data());
      RowState sa, sb;
      for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, size.width - x0);
        simd.kernel->span(y, x0, n, ax, ay, a_ok, sa);
        scalar.kernel->span(y, x0, n, bx, by, b_ok, sb);
        for (int i = 0; i < n; ++i) {
          flags_differ += (a_ok[i] != 0) != (b_ok[i] != 0);
          const size_t k = static_cast<size_t>(x0 + i);
          // Positions a filter can read (bicubic's support beyond the border included); far
          // beyond the horizon a float position is coarse in every code path and unused.
          if (!a_ok[i] || !b_ok[i] || !exact_ok[k] || !(std::abs(exact[k].x() - size.width / 2.0) < size.width / 2.0 + 8) ||
              !(std::abs(exact[k].y() - size.height / 2.0) < size.height / 2.0 + 8))
            continue;
          ++compared;
          to_scalar = std::max(to_scalar, std::hypot(double(ax[i]) - bx[i], double(ay[i]) - by[i]));
          to_exact = std::max(to_exact, std::hypot(ax[i] - exact[k].x(), ay[i] - exact[k].y()));
        }
      }
    }
    qInfo("%s: %lld compared, worst %.2e px to the scalar code, %.2e px to the exact inverse",
          simd.name.c_str(), compared, to_scalar, to_exact);
    QVERIFY(compared > size.width * size.height / 30);
    QCOMPARE(flags_differ, 0LL);
    QVERIFY2(to_scalar <= 1e-3, qPrintable(QString("to scalar %1 px").arg(to_scalar)));
    QVERIFY2(to_exact <= 1.0 / 256.0, qPrintable(QString("to exact %1 px").arg(to_exact)));
  }

  // Strong random maps and a pole through the frame: whatever is certified stays in budget, and
  // the cells the pole curve crosses are not certified.
  void certificationRefusesWhatItCannotVouchFor_data() {
    QTest::addColumn<Camera>("camera");
    QTest::addColumn<bool>("has_pole");
    const FrameSize size{400, 300};
    test::rng().seed(41);
    for (double strength : {0.1, 0.2, 0.3})
      QTest::newRow(qPrintable(QString("random %1").arg(strength)))
          << test::randomRationalCamera(size, size, strength) << false;
    Eigen::Matrix3d q0 = Eigen::Matrix3d::Zero(), q1 = q0, q2 = q0;
    q0(0, 2) = q0(2, 0) = 0.5;  // u
    q1(1, 2) = q1(2, 1) = 0.5;  // v
    q2(0, 0) = -2.0;            // 1 − 2u²: zero on two vertical lines inside the frame
    q2(2, 2) = 1.0;
    QTest::newRow("pole through frame") << Camera::rtcam({q0, q1, q2}, size, size) << true;
  }

  void certificationRefusesWhatItCannotVouchFor() {
    QFETCH(Camera, camera);
    QFETCH(bool, has_pole);
    const FrameSize size = camera.sourceSize();
    double share = 0.0;
    const double worst = worstAgainstReference(camera, size, CoordinateOptions{}, &share);
    qInfo("certified share %.3f, worst %.2e px", share, worst);
    QVERIFY2(worst <= 1.0 / 256.0, qPrintable(QString("worst %1 px").arg(worst)));
    if (has_pole) QVERIFY2(share < 1.0, qPrintable(QString("share %1").arg(share)));
  }

  // The 8-bit preview pyramid: each level the rounded 2×2 box average of the one above
  // (recomputed here), and a preview at a quarter of the photo's size samples level 2, whose
  // pixels an identity camera reproduces exactly, with alpha 255 appended.
  void storedPyramidAndPreview() {
    const int w = 204, h = 152;  // level 2 is 51×38: odd, so level 3 repeats its last column
    const std::vector<std::uint8_t> img = noiseImage(w, h, 3, -1);
    const ConstImageView base = packedView<const void>(img.data(), w, h, 3, PixelType::UInt8);
    const StoredMipPyramid pyramid(base, 16);
    QCOMPARE(pyramid.levels(), 4);  // 204, 102, 51, 26 (26 / 2 < 16 stops)
    for (int k = 1; k < pyramid.levels(); ++k) {
      const ConstImageView& up = pyramid.level(k - 1);
      const ConstImageView& lv = pyramid.level(k);
      QCOMPARE(lv.width, (up.width + 1) / 2);
      QCOMPARE(lv.height, (up.height + 1) / 2);
      for (int y = 0; y < lv.height; ++y)
        for (int x = 0; x < lv.width; ++x)
          for (int c = 0; c < 3; ++c) {
            const auto at = [&](int xx, int yy) {
              xx = std::min(xx, up.width - 1);
              yy = std::min(yy, up.height - 1);
              return static_cast<const std::uint8_t*>(up.row(yy))[xx * 3 + c];
            };
            const int want = (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1) + 2) / 4;
            QCOMPARE(int(static_cast<const std::uint8_t*>(lv.row(y))[x * 3 + c]), want);
          }
    }
    const ConstImageView& l2 = pyramid.level(2);
    std::vector<std::uint8_t> out(static_cast<size_t>(l2.width) * l2.height * 4);
    WarpSummary s;
    warpPreview(pyramid, Camera::identity({Block{BlockKind::Position, 3}}, {w, h}, {w, h}),
                packedView<void>(out.data(), l2.width, l2.height, 4, PixelType::UInt8, 3), {}, &s);
    QVERIFY2(s.note.rfind("mip level 2", 0) == 0, s.note.c_str());
    for (int y = 0; y < l2.height; ++y)
      for (int x = 0; x < l2.width; ++x) {
        const std::uint8_t* want = static_cast<const std::uint8_t*>(l2.row(y)) + x * 3;
        const std::uint8_t* got = out.data() + (static_cast<size_t>(y) * l2.width + x) * 4;
        QVERIFY2(got[0] == want[0] && got[1] == want[1] && got[2] == want[2] && got[3] == 255,
                 qPrintable(QString("pixel %1,%2").arg(x).arg(y)));
      }
  }

  // Stored-type I/O: an RGBA PNG comes back premultiplied in the stored domain and writes back
  // straight; values with alpha 255 exactly, others within the rounding of premultiplication.
  void storedImageRoundTrip() {
    const int w = 40, h = 30;
    StoredImage img = makeStoredImage(w, h, 4, 3, PixelType::UInt8);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint8_t* p = img.bytes.data() + (static_cast<size_t>(y) * w + x) * 4;
        const int a = x < 20 ? 255 : (y * 8) % 256;
        p[0] = static_cast<std::uint8_t>(x * 6 * a / 255);
        p[1] = static_cast<std::uint8_t>(y * 8 * a / 255);
        p[2] = static_cast<std::uint8_t>(((x + y) * 3) * a / 255);
        p[3] = static_cast<std::uint8_t>(a);
      }
    const std::string path = scratch("rgba.png").string();
    QVERIFY(writeStoredImage(path, std::as_const(img).view()).ok);
    const auto back = readStoredImage(path);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->channels, 4);
    QCOMPARE(back->alpha_channel, 3);
    QCOMPARE(back->type, PixelType::UInt8);
    int worst_opaque = 0, worst = 0;
    for (size_t k = 0; k < img.bytes.size(); ++k) {
      const int d = std::abs(int(img.bytes[k]) - int(back->bytes[k]));
      const size_t pixel = k / 4;
      const bool opaque = img.bytes[pixel * 4 + 3] == 255;
      (opaque ? worst_opaque : worst) = std::max(opaque ? worst_opaque : worst, d);
    }
    QCOMPARE(worst_opaque, 0);
    QVERIFY2(worst <= 1, qPrintable(QString("worst %1").arg(worst)));
    std::filesystem::remove(path);
  }

  // Identity through the stored path reproduces a 16-bit RGB PNG exactly, and a JPEG output
  // of an 8-bit source keeps its encoding (no float detour needed); EXR would not.
  void identityWarpOfStoredImageIsExact() {
    const int w = 70, h = 50;
    StoredImage img = makeStoredImage(w, h, 3, -1, PixelType::UInt16);
    for (size_t k = 0; k < img.bytes.size(); k += 2) {
      const std::uint16_t v = static_cast<std::uint16_t>((k * 2654435761u) >> 7);
      std::memcpy(img.bytes.data() + k, &v, 2);
    }
    const std::string path = scratch("rgb16.png").string();
    QVERIFY(writeStoredImage(path, std::as_const(img).view()).ok);
    const auto in = readStoredImage(path);
    QVERIFY2(in.ok(), in.status.message.c_str());
    QCOMPARE(in->type, PixelType::UInt16);
    QVERIFY(in->bytes.size() == img.bytes.size() && std::equal(img.bytes.begin(), img.bytes.end(), in->bytes.begin()));
    StoredImage out = makeStoredImage(w, h, 4, 3, PixelType::UInt16);
    WarpSummary s;
    warpImage(in->view(), Camera::identity({Block{BlockKind::Position, 3}}, {w, h}, {w, h}), out.view(), {}, &s);
    QCOMPARE(s.kernel, std::string("identity"));
    for (int p = 0; p < w * h; ++p) {
      QCOMPARE(std::memcmp(out.bytes.data() + p * 8, in->bytes.data() + p * 6, 6), 0);
      QCOMPARE(int(out.bytes[static_cast<size_t>(p) * 8 + 6]) + 256 * out.bytes[static_cast<size_t>(p) * 8 + 7], 65535);
    }
    QVERIFY(storedWriteKeepsEncoding("x.jpg", PixelType::UInt8));
    QVERIFY(storedWriteKeepsEncoding("x.tif", PixelType::Float));
    QVERIFY(!storedWriteKeepsEncoding("x.exr", PixelType::UInt8));
    QVERIFY(!storedWriteKeepsEncoding("x.png", PixelType::Float));
    QVERIFY(!formatStoresAlpha("x.jpg"));
    QVERIFY(formatStoresAlpha("x.png"));
    std::filesystem::remove(path);
  }
};

QTEST_GUILESS_MAIN(TestFastPaths)
#include "test_fast_paths.moc"
