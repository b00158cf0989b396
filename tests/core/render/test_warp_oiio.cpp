// SPDX-License-Identifier: Apache-2.0
// Acceptance: a homography warp of the bundled photo agrees with OpenImageIO's
// ImageBufAlgo::warp, the reference implementation of the same pixel conventions.
//
// How OIIO 2.4 warps (src/libOpenImageIO/imagebufalgo_xform.cpp, warp_ and filtered_sample):
// M is an Imath::M33f in ROW-vector convention mapping source to destination pixel
// coordinates; each destination pixel centre (x + 0.5, y + 0.5) goes through M⁻¹ to (s, t), and
// source pixel i is weighted by filter(i + 0.5 − s) — so pixel centres are at i + 0.5 on both
// sides, as in the engine. The weights are divided by their sum taken over ALL taps, including
// the ones outside the image that read black (WrapBlack), so borders fade like ours. The
// footprint is scaled by max(1, |ds/dx|, |ds/dy|): with a map that magnifies everywhere the
// "triangle" filter of width 2 is exactly bilinear interpolation, which is what is compared.
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/warp.h"
#include "tests/support/test_support.h"

#include <Eigen/LU>
#include <OpenImageIO/Imath.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "tests/core/render/photo_fixture.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

OIIO::ImageBuf toBuf(const ImageF& image) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT));
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.data.data());
  return buf;
}

// target_from_source in pixels: zoom 1.2 and a 5° turn about the centre, mild perspective.
Eigen::Matrix3d magnifyingHomography(double w, double h, double shift_x = 0.0) {
  const double a = 5.0 * 3.14159265358979 / 180.0;
  Eigen::Matrix3d to_centre, from_centre, m;
  to_centre << 1, 0, -w / 2, 0, 1, -h / 2, 0, 0, 1;
  from_centre << 1, 0, w / 2 + shift_x, 0, 1, h / 2, 0, 0, 1;
  m << 1.2 * std::cos(a), -1.2 * std::sin(a), 3.0,  //
      1.2 * std::sin(a), 1.2 * std::cos(a), -2.0,   //
      1.5e-4, -1.0e-4, 1.0;
  return from_centre * m * to_centre;
}

Camera cameraFromPixelHomography(const Eigen::Matrix3d& h_px, FrameSize size) {
  // Cameras are stored normalised: H_n = N · H_px · P (frames.h).
  const Eigen::Matrix3d h_n = normalizedFromPixelMatrix(size) * h_px * pixelFromNormalizedMatrix(size);
  Stage stage;
  for (const Eigen::MatrixXd& q : liftHomography(h_n)) stage.q.push_back(q);
  return Camera({Block{BlockKind::Position, 3}}, {stage}, size, size);
}

struct Comparison {
  double psnr = 0.0;
  long long pixels = 0;
};

// PSNR (peak 1, linear) over RGB of pixels at least `margin` px from every border on both
// sides, where the filters see the same taps.
Comparison compare(const ImageF& ours, const OIIO::ImageBuf& theirs, const Eigen::Matrix3d& h_px,
                   int src_w, int src_h, double margin) {
  const Eigen::Matrix3d inv = h_px.inverse();
  double sum = 0.0;
  Comparison out;
  std::vector<float> pel(static_cast<size_t>(theirs.nchannels()));
  for (int y = 0; y < ours.height; ++y) {
    for (int x = 0; x < ours.width; ++x) {
      if (x < margin || y < margin || x >= ours.width - margin || y >= ours.height - margin) continue;
      const Eigen::Vector3d s = inv * Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
      const double sx = s.x() / s.z(), sy = s.y() / s.z();
      if (sx < margin || sy < margin || sx > src_w - margin || sy > src_h - margin) continue;
      theirs.getpixel(x, y, pel.data(), theirs.nchannels());
      const float* p = ours.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        const double d = static_cast<double>(p[c]) - pel[static_cast<size_t>(c)];
        sum += d * d;
      }
      ++out.pixels;
    }
  }
  const double mse = sum / (3.0 * static_cast<double>(std::max<long long>(1, out.pixels)));
  out.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 300.0;
  return out;
}

}  // namespace

class TestWarpOiio : public QObject {
  Q_OBJECT

 private slots:
  void homographyMatchesOpenImageIO() {
    const ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const FrameSize size{photo.width, photo.height};
    const Eigen::Matrix3d h_px = magnifyingHomography(photo.width, photo.height);
    const Camera camera = cameraFromPixelHomography(h_px, size);
    QCOMPARE(analyseStructure(camera).geometry, GeometryClass::Homography);

    // The comparison is only bilinear-vs-triangle if OIIO's footprint stays 1 px everywhere.
    const Eigen::Matrix3d inv = h_px.inverse();
    double max_derivative = 0.0;
    for (int y = 0; y <= photo.height; y += 20)
      for (int x = 0; x <= photo.width; x += 20) {
        const Eigen::Vector3d s = inv * Eigen::Vector3d(x, y, 1.0);
        for (int c = 0; c < 2; ++c)
          for (int r = 0; r < 2; ++r)
            max_derivative = std::max(max_derivative,
                                      std::abs((inv(r, c) - s[r] / s.z() * inv(2, c)) / s.z()));
      }
    QVERIFY2(max_derivative < 1.0, "the test homography must magnify everywhere");

    WarpOptions options;
    options.filter = Filter::Bilinear;
    WarpSummary summary;
    const ImageF ours = warpImage(photo, camera, options, &summary);
    QCOMPARE(summary.kernel, std::string("homography"));
    QCOMPARE(ours.width, photo.width);
    QCOMPARE(ours.channels, 4);

    // Imath's M33f is row-major and multiplies row vectors: M = H_pxᵀ.
    Imath::M33f m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = static_cast<float>(h_px(c, r));
    const OIIO::ImageBuf theirs = OIIO::ImageBufAlgo::warp(toBuf(photo), m, "triangle", 2.0f, false,
                                                            OIIO::ImageBuf::WrapBlack);
    QVERIFY2(!theirs.has_error(), theirs.geterror().c_str());
    QCOMPARE(theirs.spec().width, ours.width);

    const Comparison result = compare(ours, theirs, h_px, photo.width, photo.height, 4.0);
    qInfo("homography warp vs OIIO ImageBufAlgo::warp (triangle 2): PSNR %.2f dB over %lld pixels",
          result.psnr, result.pixels);
    QVERIFY(result.pixels > photo.width * photo.height / 2);
    QVERIFY2(result.psnr >= 45.0, "our homography warp differs from OpenImageIO's");

    // The criterion can fail: the same comparison after a half-pixel shift of the camera (the
    // classic pixel-centre mistake) falls far below it.
    const Eigen::Matrix3d shifted = magnifyingHomography(photo.width, photo.height, 0.5);
    const ImageF off = warpImage(photo, cameraFromPixelHomography(shifted, size), options);
    const Comparison wrong = compare(off, theirs, h_px, photo.width, photo.height, 4.0);
    qInfo("control: a half-pixel shift gives PSNR %.2f dB", wrong.psnr);
    QVERIFY(wrong.psnr < 45.0);
  }

  // Keys a = −0.5 is OIIO's "catmull-rom" filter (width 4): the bicubic path agrees too.
  void bicubicMatchesCatmullRom() {
    const ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const FrameSize size{photo.width, photo.height};
    const Eigen::Matrix3d h_px = magnifyingHomography(photo.width, photo.height);
    WarpOptions options;
    options.filter = Filter::Bicubic;
    const ImageF ours = warpImage(photo, cameraFromPixelHomography(h_px, size), options);
    Imath::M33f m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = static_cast<float>(h_px(c, r));
    const OIIO::ImageBuf theirs = OIIO::ImageBufAlgo::warp(
        toBuf(photo), m, "catmull-rom", 4.0f, false, OIIO::ImageBuf::WrapBlack);
    QVERIFY2(!theirs.has_error(), theirs.geterror().c_str());
    const Comparison result = compare(ours, theirs, h_px, photo.width, photo.height, 4.0);
    qInfo("bicubic homography warp vs OIIO (catmull-rom 4): PSNR %.2f dB", result.psnr);
    QVERIFY(result.psnr >= 45.0);
  }
};

QTEST_GUILESS_MAIN(TestWarpOiio)
#include "test_warp_oiio.moc"
