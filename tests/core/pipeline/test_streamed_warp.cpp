// SPDX-License-Identifier: Apache-2.0
// The banded warp of photos too big to hold whole (core/pipeline/streamed_warp.h): decoded,
// rendered and encoded in bands, it writes the same samples as the whole-image warp
// (warpImage on the photo read whole, written by writeStoredImage), for a strong lens with
// regions without a preimage, a mild rational lens on 16-bit RGBA, a homography, a whole-pixel
// translation (the copy path) and float EXR, while holding a window of the photo's rows only.
// A camera that reads the photo out of order is refused before anything is written, naming
// the memory it would need; cameras with layers are not streamed.
#include "core/effects/effect_table.h"
#include "core/io/stored_image.h"
#include "core/pipeline/streamed_warp.h"
#include "core/render/warp.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cstdint>
#include <cstring>
#include <filesystem>

using namespace artcam;

Q_DECLARE_METATYPE(artcam::Artcam)
Q_DECLARE_METATYPE(artcam::Filter)
Q_DECLARE_METATYPE(artcam::PixelType)

namespace {

constexpr FrameSize kFrame{512, 256};  // s = 256: whole-pixel shifts are exact in the frame

std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("artcam-streamed-" + std::to_string(QCoreApplication::applicationPid()) + "-" + name))
      .string();
}

// A photo of busy, distinct samples (a hash of position and channel), alpha varying where there
// is alpha, written by the stored writer.
bool writePhoto(const std::string& path, int channels, int alpha, PixelType type) {
  StoredImage image = makeStoredImage(kFrame.width, kFrame.height, channels, alpha, type);
  const float full = pixelTypeFullScale(type);
  for (int y = 0; y < kFrame.height; ++y)
    for (int x = 0; x < kFrame.width; ++x)
      for (int c = 0; c < channels; ++c) {
        const unsigned h = (static_cast<unsigned>(x) * 73856093u) ^ (static_cast<unsigned>(y) * 19349663u) ^
                           (static_cast<unsigned>(c) * 83492791u);
        float v = c == alpha ? 0.5f + 0.5f * static_cast<float>(h % 1000) / 999.0f
                             : static_cast<float>(h % 1000) / 999.0f;
        const size_t at = (static_cast<size_t>(y) * kFrame.width + x) * channels + c;
        if (type == PixelType::UInt8) image.bytes.data()[at] = static_cast<std::uint8_t>(v * full + 0.5f);
        else if (type == PixelType::UInt16) {
          const auto s = static_cast<std::uint16_t>(v * full + 0.5f);
          std::memcpy(image.bytes.data() + at * 2, &s, 2);
        } else {
          std::memcpy(image.bytes.data() + at * 4, &v, 4);
        }
      }
  // Stored alpha is premultiplied (stored_image.h); a file stores it straight, so premultiply.
  if (alpha >= 0 && type == PixelType::UInt16) {
    auto* p = reinterpret_cast<std::uint16_t*>(image.bytes.data());
    for (size_t k = 0; k < static_cast<size_t>(kFrame.width) * kFrame.height; ++k, p += channels)
      for (int c = 0; c < channels; ++c)
        if (c != alpha) p[c] = static_cast<std::uint16_t>(std::lround(p[c] * (p[alpha] / 65535.0f)));
  }
  return writeStoredImage(path, std::as_const(image).view()).ok;
}

// The whole-image warp as `artcam warp` runs it: read whole, warpImage into the photo's
// channels plus alpha where the format stores it, written by the stored writer.
Status wholeWarp(const std::string& in, const Camera& camera, Filter filter, const std::string& out) {
  auto photo = readStoredImage(in);
  if (!photo) return photo.status;
  const bool add_alpha = photo->alpha_channel < 0 && formatStoresAlpha(out);
  StoredImage result = makeStoredImage(kFrame.width, kFrame.height, photo->channels + (add_alpha ? 1 : 0),
                                       add_alpha ? photo->channels : photo->alpha_channel, photo->type);
  WarpOptions options;
  options.filter = filter;
  warpImage(std::as_const(*photo).view(), camera, result.view(), options);
  return writeStoredImage(out, std::as_const(result).view(), &photo->info);
}

// Every colour sample equal; alpha equal, or full where one side has none.
QString compareFiles(const std::string& a_path, const std::string& b_path) {
  auto a = readStoredImage(a_path), b = readStoredImage(b_path);
  if (!a || !b) return "unreadable";
  if (a->width != b->width || a->height != b->height || a->type != b->type) return "shapes differ";
  const int colours_a = a->alpha_channel >= 0 ? a->channels - 1 : a->channels;
  const int colours_b = b->alpha_channel >= 0 ? b->channels - 1 : b->channels;
  if (colours_a != colours_b) return "colour channels differ";
  const int size = pixelTypeSize(a->type);
  const float full = pixelTypeFullScale(a->type);
  auto sample = [&](const StoredImage& im, int x, int y, int c) {
    const size_t at = ((static_cast<size_t>(y) * im.width + x) * im.channels + c) * size;
    if (im.type == PixelType::UInt8) return static_cast<float>(im.bytes.data()[at]);
    if (im.type == PixelType::UInt16) { std::uint16_t v; std::memcpy(&v, im.bytes.data() + at, 2); return static_cast<float>(v); }
    float v;
    std::memcpy(&v, im.bytes.data() + at, 4);
    return v;
  };
  for (int y = 0; y < a->height; ++y)
    for (int x = 0; x < a->width; ++x) {
      for (int c = 0; c < colours_a; ++c)
        if (sample(*a, x, y, c) != sample(*b, x, y, c))
          return QString("pixel (%1, %2) channel %3: %4 vs %5").arg(x).arg(y).arg(c)
              .arg(sample(*a, x, y, c)).arg(sample(*b, x, y, c));
      const float alpha_a = a->alpha_channel >= 0 ? sample(*a, x, y, a->alpha_channel) : full;
      const float alpha_b = b->alpha_channel >= 0 ? sample(*b, x, y, b->alpha_channel) : full;
      if (alpha_a != alpha_b) return QString("pixel (%1, %2) alpha: %3 vs %4").arg(x).arg(y).arg(alpha_a).arg(alpha_b);
    }
  return {};
}

// n_k = p_k · (u², uv, u, v², v, 1) in the normalised frame.
Camera quadraticCamera(const double p[3][6]) {
  std::vector<Eigen::Matrix3d> q(3);
  for (int k = 0; k < 3; ++k)
    q[static_cast<size_t>(k)] << p[k][0], p[k][1] / 2, p[k][2] / 2, p[k][1] / 2, p[k][3],
        p[k][4] / 2, p[k][2] / 2, p[k][4] / 2, p[k][5];
  return Camera::rtcam(q, kFrame, kFrame);
}

Camera mildLens() {
  const double p[3][6] = {{0.030, 0.020, 1.000, -0.010, 0.010, 0.005},
                          {0.010, -0.020, 0.015, 0.030, 0.980, -0.004},
                          {0.020, 0.010, 0.040, -0.020, -0.030, 1.000}};
  return quadraticCamera(p);
}

// Target = source + (5, −7) px: 5/256 and 7/256 are exact in the normalised frame.
Camera shift() {
  const double p[3][6] = {{0, 0, 1, 0, 0, 5.0 / 256}, {0, 0, 0, 0, 1, -7.0 / 256}, {0, 0, 0, 0, 0, 1}};
  return quadraticCamera(p);
}

// Upside down: output row y reads photo row h − 1 − y, so the first band needs the last rows.
Camera flip() {
  const double p[3][6] = {{0, 0, 1, 0, 0, 0}, {0, 0, 0, 0, -1, 0}, {0, 0, 0, 0, 0, 1}};
  return quadraticCamera(p);
}

}  // namespace

class TestStreamedWarp : public QObject {
  Q_OBJECT

 private slots:
  void sameSamplesAsTheWholeImageWarp_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<Artcam>("camera");
    QTest::addColumn<Filter>("filter");
    QTest::addColumn<int>("channels");
    QTest::addColumn<int>("alpha");
    QTest::addColumn<PixelType>("type");
    QTest::addColumn<QString>("format");
    QTest::newRow("strong barrel, RGB8, bilinear")
        << "barrel" << buildEffect("barrel", {{"k", {-0.6}}}, kFrame) << Filter::Bilinear << 3 << -1
        << PixelType::UInt8 << "png";
    QTest::newRow("mild lens, RGBA16, bicubic")
        << "lens" << Artcam(mildLens()) << Filter::Bicubic << 4 << 3 << PixelType::UInt16 << "png";
    QTest::newRow("homography, grey8, nearest")
        << "homography" << Artcam(test::randomHomographyCamera(kFrame, kFrame)) << Filter::Nearest << 1
        << -1 << PixelType::UInt8 << "png";
    QTest::newRow("whole-pixel shift, RGB8 (row copies)")
        << "shift" << Artcam(shift()) << Filter::Bilinear << 3 << -1 << PixelType::UInt8 << "tif";
    QTest::newRow("mild lens, float EXR, bilinear")
        << "exr" << Artcam(mildLens()) << Filter::Bilinear << 3 << -1 << PixelType::Float << "exr";
  }

  void sameSamplesAsTheWholeImageWarp() {
    QFETCH(QString, name);
    QFETCH(Artcam, camera);
    QFETCH(Filter, filter);
    QFETCH(int, channels);
    QFETCH(int, alpha);
    QFETCH(PixelType, type);
    QFETCH(QString, format);
    const std::string ext = "." + format.toStdString();
    const std::string photo = scratch(name.toStdString() + "-in" + ext);
    const std::string whole = scratch(name.toStdString() + "-whole" + ext);
    const std::string streamed = scratch(name.toStdString() + "-streamed" + ext);
    QVERIFY(writePhoto(photo, channels, alpha, type));
    const Status w = wholeWarp(photo, camera.main(), filter, whole);
    QVERIFY2(w.ok, w.message.c_str());

    auto reader = StoredImageReader::open(photo);
    QVERIFY2(reader.ok(), reader.status.message.c_str());
    StreamedWarpOptions options;
    options.warp.filter = filter;
    StreamedWarpSummary summary;
    const Status s = streamWarp(**reader, camera, streamed, options, &summary);
    QVERIFY2(s.ok, s.message.c_str());
    QCOMPARE(summary.size, kFrame);
    // A window, not the photo: these cameras read rows near the band's own.
    QVERIFY2(summary.window_rows > 0 && summary.window_rows < kFrame.height,
             qPrintable(QString::number(summary.window_rows)));
    const QString difference = compareFiles(whole, streamed);
    QVERIFY2(difference.isEmpty(), qPrintable(difference));
    if (name == "barrel") QVERIFY(summary.transparent_pixels > 0);
    for (const std::string& f : {photo, whole, streamed}) std::filesystem::remove(f);
  }

  void outOfOrderReadsAreRefusedBeforeWriting() {
    const std::string photo = scratch("flip-in.png"), out = scratch("flip-out.png");
    QVERIFY(writePhoto(photo, 3, -1, PixelType::UInt8));
    auto reader = StoredImageReader::open(photo);
    QVERIFY(reader.ok());
    StreamedWarpOptions options;
    options.memory_budget_bytes = 200.0 * 1024;  // half the photo's rows
    const Status s = streamWarp(**reader, Artcam(flip()), out, options);
    QVERIFY(!s.ok);
    QVERIFY2(s.message.find("cannot warp in bands") != std::string::npos &&
                 s.message.find("memory budget of 0.2 MiB") != std::string::npos &&
                 s.message.find("256 rows") != std::string::npos &&
                 s.message.find(photo) == 0,
             s.message.c_str());
    QVERIFY(!std::filesystem::exists(out));
    // The same camera streams when the budget holds every row.
    auto again = StoredImageReader::open(photo);
    QVERIFY(again.ok());
    options.memory_budget_bytes = 0.0;
    QVERIFY(streamWarp(**again, Artcam(flip()), out, options).ok);
    QVERIFY(std::filesystem::exists(out));
    std::filesystem::remove(photo);
    std::filesystem::remove(out);
  }

  // A progress callback that says stop: the summary says cancelled and no file is left.
  void cancelLeavesNoFile() {
    const std::string photo = scratch("cancel-in.png"), out = scratch("cancel-out.png");
    QVERIFY(writePhoto(photo, 3, -1, PixelType::UInt8));
    auto reader = StoredImageReader::open(photo);
    QVERIFY(reader.ok());
    StreamedWarpOptions options;
    int calls = 0;
    options.warp.progress = [&calls](double) { return ++calls < 6; };  // past the plan, mid-write
    StreamedWarpSummary summary;
    const Status s = streamWarp(**reader, Artcam(mildLens()), out, options, &summary);
    QVERIFY(!s.ok);
    QVERIFY(summary.cancelled);
    QVERIFY2(s.message.find("cancelled") != std::string::npos, s.message.c_str());
    QVERIFY(!std::filesystem::exists(out));
    std::filesystem::remove(photo);
  }

  void layeredCamerasAreNotStreamed() {
    const Artcam aberration = buildEffect("chromatic-aberration", {}, kFrame);
    QVERIFY(!streamableCamera(aberration));
    QVERIFY(streamableCamera(Artcam(mildLens())));
    const std::string photo = scratch("ca-in.png"), out = scratch("ca-out.png");
    QVERIFY(writePhoto(photo, 3, -1, PixelType::UInt8));
    auto reader = StoredImageReader::open(photo);
    QVERIFY(reader.ok());
    const Status s = streamWarp(**reader, aberration, out, {});
    QVERIFY2(!s.ok && s.message.find("layers") != std::string::npos, s.message.c_str());
    QVERIFY(!std::filesystem::exists(out));
    std::filesystem::remove(photo);
  }

  // A window that misses rows the band reads is refused, not sampled as black.
  void aWindowMissingRowsIsRefused() {
    const BandWarp band(mildLens(), kFrame, kFrame, {});
    const BandWarp::Rows rows = band.sourceRows(100, 116);
    QVERIFY(!rows.empty() && rows.first > 0 && rows.last < kFrame.height);
    std::vector<std::uint8_t> window(static_cast<size_t>(kFrame.width) * 3 * kFrame.height);
    std::vector<std::uint8_t> out(static_cast<size_t>(kFrame.width) * 4 * 16);
    const ImageView out_view = packedView<void>(out.data(), kFrame.width, 16, 4, PixelType::UInt8, 3);
    const ConstImageView holds = packedView<const void>(window.data(), kFrame.width,
                                                        rows.last - rows.first, 3, PixelType::UInt8, -1);
    band.render(holds, rows.first, 100, 116, out_view);  // the rows it asked for: fine
    const ConstImageView short_by_one = packedView<const void>(
        window.data(), kFrame.width, rows.last - rows.first - 5, 3, PixelType::UInt8, -1);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             band.render(short_by_one, rows.first, 100, 116, out_view));
  }
};

QTEST_GUILESS_MAIN(TestStreamedWarp)
#include "test_streamed_warp.moc"
