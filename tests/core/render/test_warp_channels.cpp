// SPDX-License-Identifier: Apache-2.0
// warpChannels (one position camera per colour channel: chromatic aberration) against what it
// means: each channel camera's own warpImage of the whole photo, channel c taken from camera c's
// render, alpha the least of the renders' alphas and each colour rescaled to it (warp.h). The
// 8-bit nearest and bilinear paths sample interior spans one channel at a time; every pixel
// must still equal the reference exactly, interior and border, for every filter and type, with
// and without the AVX2 clone.
#include "core/io/stored_image.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

using namespace artcam;
using namespace artcam::test;

namespace {

// Noise, so a wrong channel, tap or stride shows at every pixel.
StoredImage noise(int w, int h, int channels, PixelType type) {
  StoredImage image = makeStoredImage(w, h, channels, -1, type);
  std::uint32_t state = 12345;
  const auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return state >> 16;
  };
  const size_t samples = static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels);
  for (size_t i = 0; i < samples; ++i) {
    if (type == PixelType::UInt8) image.bytes[i] = static_cast<std::uint8_t>(next() & 255u);
    else {
      const auto v = static_cast<std::uint16_t>(next());
      std::memcpy(image.bytes.data() + i * 2, &v, 2);
    }
  }
  return image;
}

double sample(const StoredImage& image, int x, int y, int c) {
  const size_t at = (static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)) *
                        static_cast<size_t>(image.channels) + static_cast<size_t>(c);
  if (image.type == PixelType::UInt8) return image.bytes[at];
  std::uint16_t v;
  std::memcpy(&v, image.bytes.data() + at * 2, 2);
  return v;
}

}  // namespace

class TestWarpChannels : public QObject {
  Q_OBJECT

 private slots:
  void eachChannelIsItsCamerasWarp_data() {
    QTest::addColumn<QString>("filter");
    QTest::addColumn<bool>("sixteen");
    QTest::addColumn<bool>("scalar");
    QTest::addColumn<double>("blue_scale");
    QTest::addColumn<bool>("avx512");
    QTest::newRow("bilinear 8-bit") << "bilinear" << false << false << 0.987 << true;
    // The AVX2 clone where the AVX-512 kernel would take the groups (the same on a CPU
    // without AVX-512).
    QTest::newRow("bilinear 8-bit AVX2") << "bilinear" << false << false << 0.987 << false;
    QTest::newRow("bilinear 8-bit scalar") << "bilinear" << false << true << 0.987 << true;
    QTest::newRow("nearest 8-bit") << "nearest" << false << false << 0.987 << true;
    QTest::newRow("bicubic 8-bit") << "bicubic" << false << false << 0.987 << true;
    QTest::newRow("bilinear 16-bit") << "bilinear" << true << false << 0.987 << true;
    // Blue's source positions 1/0.68 px apart: four pixels' taps no longer fit one 16-byte
    // window, so the AVX2 clone reads each tap by itself (and the AVX-512 kernel hands those
    // groups to it).
    QTest::newRow("bilinear 8-bit, blue minified") << "bilinear" << false << false << 0.68 << true;
    QTest::newRow("bilinear 8-bit, blue minified, AVX2") << "bilinear" << false << false << 0.68 << false;
  }

  void eachChannelIsItsCamerasWarp() {
    QFETCH(QString, filter);
    QFETCH(bool, sixteen);
    QFETCH(bool, scalar);
    QFETCH(double, blue_scale);
    QFETCH(bool, avx512);
    const int w = 301, h = 203;  // spans of 64 and a ragged last one
    const PixelType type = sixteen ? PixelType::UInt16 : PixelType::UInt8;
    const StoredImage photo = noise(w, h, 3, type);
    // Red scaled up about the centre (its border leaves the frame), green unmoved, blue scaled
    // down and shifted (a transparent margin), all by sub-pixel amounts.
    Eigen::Matrix3d red, green, blue;
    red << 1.013, 0, 0.002, 0, 1.013, -0.001, 0, 0, 1;
    green.setIdentity();
    blue << blue_scale, 0.001, -0.004, 0, blue_scale, 0.003, 0, 0, 1;
    const std::vector<Camera> cameras = {homographyCamera(red, {w, h}, {w, h}),
                                         homographyCamera(green, {w, h}, {w, h}),
                                         homographyCamera(blue, {w, h}, {w, h})};
    WarpOptions options;
    options.filter = *filterFromName(filter.toStdString());
    options.coordinates.scalar_only = scalar;  // also keeps the sampler off its SIMD clones
    options.coordinates.allow_avx512 = avx512;

    StoredImage out = makeStoredImage(w, h, 4, 3, type, PixelBuffer::Init::Uninitialised);
    std::memset(out.bytes.data(), 0xCD, out.bytes.size());
    WarpSummary summary;
    warpChannels(photo.view(), cameras, out.view(), options, &summary);

    std::vector<StoredImage> each;
    for (const Camera& camera : cameras) {
      each.push_back(makeStoredImage(w, h, 4, 3, type));
      warpImage(photo.view(), camera, each.back().view(), options);
    }
    const double full = pixelTypeFullScale(type);
    long long mismatches = 0, interior = 0, border = 0, transparent = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double least = full;
        for (const StoredImage& e : each) least = std::min(least, sample(e, x, y, 3));
        (least == full ? interior : border) += 1;
        transparent += least == 0;
        for (int c = 0; c < 3; ++c) {
          const double a_c = sample(each[static_cast<size_t>(c)], x, y, 3);
          const double v = sample(each[static_cast<size_t>(c)], x, y, c);
          // The integer rescale of warp.cpp's merge, v · least / a_c rounded to nearest.
          const double expected = a_c == least ? v : (a_c == 0 ? 0 : std::floor((v * least + std::floor(a_c / 2)) / a_c));
          mismatches += sample(out, x, y, c) != expected;
        }
        mismatches += sample(out, x, y, 3) != least;
      }
    QVERIFY(interior > w * h / 3);  // the test covers both kinds of pixel
    QVERIFY(border > 0);
    QCOMPARE(summary.transparent_pixels, transparent);
    QCOMPARE(mismatches, 0LL);
  }

  // An output without alpha (a JPEG's RGB) holds the colours of the output with alpha, as
  // they are (premultiplied: over black), for every path that writes them.
  void withoutAlphaTheColoursOfTheMerge_data() {
    QTest::addColumn<QString>("filter");
    QTest::addColumn<bool>("sixteen");
    QTest::addColumn<bool>("scalar");
    QTest::newRow("bilinear 8-bit") << "bilinear" << false << false;
    QTest::newRow("bilinear 8-bit scalar") << "bilinear" << false << true;
    QTest::newRow("nearest 8-bit") << "nearest" << false << false;
    QTest::newRow("bilinear 16-bit") << "bilinear" << true << false;
  }

  void withoutAlphaTheColoursOfTheMerge() {
    QFETCH(QString, filter);
    QFETCH(bool, sixteen);
    QFETCH(bool, scalar);
    const int w = 301, h = 203;
    const PixelType type = sixteen ? PixelType::UInt16 : PixelType::UInt8;
    const StoredImage photo = noise(w, h, 3, type);
    Eigen::Matrix3d red, blue;
    // Margins of several pixels where red or blue leaves the frame (the camera's frames are
    // normalised: 0.01 is about 1.5 px here).
    red << 1.04, 0, 0.02, 0, 1.04, -0.015, 0, 0, 1;
    blue << 0.96, 0.001, 0.025, 0, 0.96, 0.017, 0, 0, 1;
    const std::vector<Camera> cameras = {homographyCamera(red, {w, h}, {w, h}),
                                         homographyCamera(Eigen::Matrix3d::Identity(), {w, h}, {w, h}),
                                         homographyCamera(blue, {w, h}, {w, h})};
    WarpOptions options;
    options.filter = *filterFromName(filter.toStdString());
    options.coordinates.scalar_only = scalar;
    StoredImage with_alpha = makeStoredImage(w, h, 4, 3, type);
    StoredImage without = makeStoredImage(w, h, 3, -1, type, PixelBuffer::Init::Uninitialised);
    std::memset(without.bytes.data(), 0xCD, without.bytes.size());
    WarpSummary a, b;
    warpChannels(photo.view(), cameras, with_alpha.view(), options, &a);
    warpChannels(photo.view(), cameras, without.view(), options, &b);
    const double full = pixelTypeFullScale(type);
    long long mismatches = 0, transparent = 0, partial = 0, opaque = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double alpha = sample(with_alpha, x, y, 3);
        (alpha == 0 ? transparent : alpha == full ? opaque : partial) += 1;
        for (int c = 0; c < 3; ++c) mismatches += sample(without, x, y, c) != sample(with_alpha, x, y, c);
      }
    // Every kind of pixel is covered: the interior, the margins and (bilinear) the edge
    // between them, where the taps straddle the frame.
    QVERIFY2(opaque > w * h / 2 && transparent > 0 && (partial > 0 || filter == "nearest"),
             qPrintable(QString("%1 opaque, %2 transparent, %3 partial").arg(opaque).arg(transparent).arg(partial)));
    QCOMPARE(b.transparent_pixels, a.transparent_pixels);
    QCOMPARE(mismatches, 0LL);
  }
};

QTEST_GUILESS_MAIN(TestWarpChannels)
#include "test_warp_channels.moc"
