// SPDX-License-Identifier: Apache-2.0
// warpImage writes every output pixel, transparent ones included (warp.h), which is what lets
// `artcam warp` hand it an uninitialised output (pixel_buffer.h). The truth is the same render
// into a zeroed output: an output filled with a garbage byte first must come out identical, for
// every filter, the whole-pixel copy, an added alpha channel and 16-bit samples.
#include "core/io/stored_image.h"
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"

#include <QtTest/QtTest>

#include <cmath>
#include <cstring>

using namespace artcam;
using namespace artcam::test;

namespace {

StoredImage texture(int w, int h, int channels, PixelType type) {
  StoredImage image = makeStoredImage(w, h, channels, -1, type);
  const ImageF source = syntheticImage(w, h, channels);
  const float full = pixelTypeFullScale(type);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        const float v = std::round(source.pixel(x, y)[c] * full);
        const size_t at = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) *
                              static_cast<size_t>(channels) + static_cast<size_t>(c);
        if (type == PixelType::UInt8) image.bytes[at] = static_cast<std::uint8_t>(v);
        else {
          const auto v16 = static_cast<std::uint16_t>(v);
          std::memcpy(image.bytes.data() + at * 2, &v16, 2);
        }
      }
  return image;
}

}  // namespace

class TestWarpWritesEveryPixel : public QObject {
  Q_OBJECT

 private slots:
  void garbageOutputComesOutAsZeroedOutput_data() {
    QTest::addColumn<QString>("filter");
    QTest::addColumn<bool>("copy");
    QTest::addColumn<int>("out_channels");
    QTest::addColumn<bool>("sixteen");
    QTest::newRow("bilinear, alpha added") << "bilinear" << false << 4 << false;
    QTest::newRow("bilinear, no alpha") << "bilinear" << false << 3 << false;
    QTest::newRow("nearest") << "nearest" << false << 4 << false;
    QTest::newRow("bicubic") << "bicubic" << false << 4 << false;
    QTest::newRow("bilinear 16-bit") << "bilinear" << false << 4 << true;
    QTest::newRow("whole-pixel copy") << "bilinear" << true << 4 << false;
  }

  void garbageOutputComesOutAsZeroedOutput() {
    QFETCH(QString, filter);
    QFETCH(bool, copy);
    QFETCH(int, out_channels);
    QFETCH(bool, sixteen);
    const int w = 173, h = 119;
    const PixelType type = sixteen ? PixelType::UInt16 : PixelType::UInt8;
    const StoredImage source = texture(w, h, 3, type);
    // A rotation with perspective that leaves corners of the output without a preimage, or a
    // whole-pixel shift (which copies rows) that leaves a border.
    Eigen::Matrix3d h_n;
    if (copy)
      h_n << 1, 0, 20.0 / (w / 2.0), 0, 1, -7.0 / (w / 2.0), 0, 0, 1;
    else
      h_n << std::cos(0.3), -std::sin(0.3), 0.05, std::sin(0.3), std::cos(0.3), -0.02, 0.1, 0.05, 1;
    const Camera camera = homographyCamera(h_n, {w, h}, {w, h});
    WarpOptions options;
    options.filter = *filterFromName(filter.toStdString());
    const int alpha = out_channels == 4 ? 3 : -1;

    StoredImage zeroed = makeStoredImage(w, h, out_channels, alpha, type);
    StoredImage garbage =
        makeStoredImage(w, h, out_channels, alpha, type, PixelBuffer::Init::Uninitialised);
    std::memset(garbage.bytes.data(), 0xCD, garbage.bytes.size());
    WarpSummary a, b;
    warpImage(source.view(), camera, zeroed.view(), options, &a);
    warpImage(source.view(), camera, garbage.view(), options, &b);
    if (copy) QCOMPARE(a.kernel, std::string("translation-copy"));
    if (out_channels == 4) QVERIFY(a.transparent_pixels > 0);  // there are pixels to leave
    QCOMPARE(a.transparent_pixels, b.transparent_pixels);
    QVERIFY(std::memcmp(zeroed.bytes.data(), garbage.bytes.data(), zeroed.bytes.size()) == 0);
  }
};

QTEST_GUILESS_MAIN(TestWarpWritesEveryPixel)
#include "test_warp_writes_every_pixel.moc"
