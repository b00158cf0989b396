// SPDX-License-Identifier: Apache-2.0
// What an OpenEXR plate holds beside its colour, through artcam warp: ID-like channels (an
// object ID, an index, Cryptomatte hashes, integer channels) sampled at the nearest texel, each
// channel's stored type kept (half RGBA beside a float Z), and every part of a multi-part file
// warped (or, into a format of one part, named as left out in one warning line), and overscan
// (a data window beyond the display window) kept.
//
// Truths: the source point of each output pixel comes from the homography's pixel matrix here,
// not from the code under test; the nearest texel is the one containing it (pixel centres at
// i + 0.5). Files are made and read back with OpenImageIO directly.
#include "tests/app/cli_run.h"

#include "core/io/artcam_file.h"
#include "core/model/camera.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <OpenImageIO/imageio.h>

#include <Eigen/Dense>

#include <QFile>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <vector>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 64, kH = 48;

Eigen::Matrix3d targetFromSourcePx() {
  Eigen::Matrix3d h;
  h << 1.07, 0.04, -2.9,  //
      -0.03, 0.95, 2.2,   //
      1.5e-4, -1.0e-4, 1.0;
  return h;
}

bool writeHomographyCamera(const QString& path) {
  using namespace artcam;
  const FrameSize frame{kW, kH};
  const Eigen::Matrix3d n = pixelFromNormalizedMatrix(frame);
  const Eigen::Matrix3d h_normalised = n.inverse() * targetFromSourcePx() * n;
  std::vector<Eigen::Matrix3d> q;
  for (const Eigen::MatrixXd& m : liftHomography(h_normalised)) q.emplace_back(m);
  return writeArtcam(path.toStdString(), Artcam(Camera::rtcam(q, frame, frame))).ok;
}

// IDs in blocks of 5x4 texels, so that a texel and its neighbours differ and interpolation
// shows; the Cryptomatte rank channel holds a float hash (any bit pattern), the coverage a
// fraction, the index a small count, the integer channel a uint32 label.
float objectId(int x, int y) { return static_cast<float>(1 + x / 5 + 13 * (y / 4)); }
float cryptoHash(int x, int y) {
  std::uint32_t bits = static_cast<std::uint32_t>(objectId(x, y)) * 2654435761u;
  bits = (bits & 0x807fffffu) | 0x3f000000u;  // a finite float in [0.5, 1) or (-1, -0.5]
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// In the order OpenImageIO reads an EXR's channels back (colour and alpha, then by name); the
// uint32 channel last, where readBack reads it as integers.
const std::vector<std::string> kNames = {
    "R", "G", "B", "A", "CryptoObject00.R", "N.x", "crypto.id", "obj.index", "object.id"};
enum Channel { kHash = 4, kNx = 5, kId = 6, kIndex = 7 };

bool writeIdPlate(const QString& path) {
  OIIO::ImageSpec spec(kW, kH, static_cast<int>(kNames.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = kNames;
  spec.alpha_channel = 3;
  spec.channelformats.assign(kNames.size(), OIIO::TypeDesc::FLOAT);
  spec.channelformats.back() = OIIO::TypeDesc::UINT32;
  std::vector<float> pixels;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float id = objectId(x, y);
      const float values[] = {0.4f,
                              0.5f,
                              0.6f,
                              1.0f,
                              cryptoHash(x, y),
                              static_cast<float>(x) / kW,
                              id,
                              std::fmod(id, 7.0f)};
      pixels.insert(pixels.end(), values, values + 8);
    }
  // The uint32 channel through a buffer of its own type: the file's integers, not scaled floats.
  std::vector<unsigned char> native;
  const size_t pixel_bytes = 8 * sizeof(float) + sizeof(std::uint32_t);
  native.resize(static_cast<size_t>(kW) * kH * pixel_bytes);
  for (size_t p = 0; p < static_cast<size_t>(kW) * kH; ++p) {
    std::memcpy(&native[p * pixel_bytes], &pixels[p * 8], 8 * sizeof(float));
    const std::uint32_t label = static_cast<std::uint32_t>(pixels[p * 8 + kId]) * 3u;
    std::memcpy(&native[p * pixel_bytes + 8 * sizeof(float)], &label, sizeof label);
  }
  auto out = OIIO::ImageOutput::create(path.toStdString());
  return out && out->open(path.toStdString(), spec) &&
         out->write_image(OIIO::TypeDesc::UNKNOWN, native.data()) && out->close();
}

float depthValue(int x, int y) { return static_cast<float>(1 + x + kW * y); }

// Part "beauty" (half RGB), then part "depthpass": Z and an object ID, float.
bool writeTwoParts(const QString& path) {
  OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(kW, kH, 3, OIIO::TypeDesc::HALF),
                              OIIO::ImageSpec(kW, kH, 2, OIIO::TypeDesc::FLOAT)};
  specs[0].attribute("name", "beauty");
  specs[1].attribute("name", "depthpass");
  specs[1].channelnames = {"Z", "object.id"};
  const std::vector<float> rgb(static_cast<size_t>(kW) * kH * 3, 0.5f);
  std::vector<float> aux;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      aux.push_back(depthValue(x, y));
      aux.push_back(objectId(x, y));
    }
  const std::string file = path.toStdString();
  auto out = OIIO::ImageOutput::create(file);
  return out && out->supports("multiimage") && out->open(file, 2, specs) &&
         out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) &&
         out->open(file, specs[1], OIIO::ImageOutput::AppendSubimage) &&
         out->write_image(OIIO::TypeDesc::FLOAT, aux.data()) && out->close();
}

struct ReadBack {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
  std::vector<std::uint32_t> labels;  // the last channel as its stored integers, when uint32
};
ReadBack readBack(const QString& path) {
  ReadBack r;
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return r;
  r.spec = in->spec();
  const size_t n = static_cast<size_t>(r.spec.image_pixels());
  r.pixels.resize(n * static_cast<size_t>(r.spec.nchannels));
  if (!in->read_image(0, 0, 0, r.spec.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data()))
    r.pixels.clear();
  r.labels.resize(n);
  if (!in->read_image(0, 0, r.spec.nchannels - 1, r.spec.nchannels, OIIO::TypeDesc::UINT32,
                      r.labels.data()))
    r.labels.clear();
  return r;
}

}  // namespace

class TestCliExrParts : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeHomographyCamera(path("h.artcam")));
    QVERIFY(writeIdPlate(path("ids.exr")));
  }

  // Every ID-like channel holds, at each output pixel, its value at the texel containing the
  // pixel's source point: integers stay integers equal to the source's, hashes stay hashes.
  // N.x, a quantity, is still interpolated (its value at the source point).
  void idChannelsAreSampledAtTheNearestTexel_data() {
    QTest::addColumn<QStringList>("options");
    QTest::newRow("stored float path") << QStringList{};
    QTest::newRow("linear float path") << QStringList{"--colourspace", "srgb"};
    QTest::newRow("bicubic") << QStringList{"--filter", "bicubic"};
  }
  void idChannelsAreSampledAtTheNearestTexel() {
    QFETCH(QStringList, options);
    const QString out = path("ids-out.exr");
    QFile::remove(out);
    const Run r = artcamCli(
        QStringList{"warp", path("ids.exr"), path("h.artcam"), "-o", out, "-q"} + options);
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ReadBack back = readBack(out);
    QVERIFY(!back.pixels.empty() && !back.labels.empty());
    QCOMPARE(back.spec.channelnames, kNames);
    const Eigen::Matrix3d source_from_target = targetFromSourcePx().inverse();
    const size_t n = kNames.size();
    int checked = 0, non_integer = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const Eigen::Vector3d s = source_from_target * Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
        const double sx = s.x() / s.z(), sy = s.y() / s.z();
        if (sx < 1.0 || sy < 1.0 || sx > kW - 1.0 || sy > kH - 1.0) continue;
        const float* px = &back.pixels[(static_cast<size_t>(y) * kW + static_cast<size_t>(x)) * n];
        if (px[kId] != std::floor(px[kId]) || px[kIndex] != std::floor(px[kIndex])) ++non_integer;
        const double fx = sx - std::floor(sx), fy = sy - std::floor(sy);
        if (fx < 1e-3 || fx > 1 - 1e-3 || fy < 1e-3 || fy > 1 - 1e-3) continue;
        const int tx = static_cast<int>(std::floor(sx)), ty = static_cast<int>(std::floor(sy));
        const float id = objectId(tx, ty);
        const std::uint32_t label =
            back.labels[static_cast<size_t>(y) * kW + static_cast<size_t>(x)];
        QVERIFY2(px[kId] == id && px[kIndex] == std::fmod(id, 7.0f) &&
                     px[kHash] == cryptoHash(tx, ty) &&
                     label == static_cast<std::uint32_t>(id) * 3u,
                 qPrintable(QString("output (%1, %2), source (%3, %4): id %5 index %6 hash %7 "
                                    "label %8; expected id %9")
                                .arg(x)
                                .arg(y)
                                .arg(sx)
                                .arg(sy)
                                .arg(double(px[kId]))
                                .arg(double(px[kIndex]))
                                .arg(double(px[kHash]))
                                .arg(label)
                                .arg(double(id))));
        // N.x interpolated: its value at the source point (bilinear of x/64 is exact).
        if (!options.contains("bicubic"))
          QVERIFY2(std::abs(px[kNx] - (sx - 0.5) / kW) < 1e-4,
                   qPrintable(QString("N.x %1 at source x %2").arg(double(px[kNx])).arg(sx)));
        ++checked;
      }
    QCOMPARE(non_integer, 0);
    QVERIFY2(checked > kW * kH / 2, qPrintable(QString::number(checked)));
    // The integer channel is written as the file stored it (its labels read back as uint32).
    QCOMPARE(back.spec.channelformat(static_cast<int>(kNames.size()) - 1),
             OIIO::TypeDesc(OIIO::TypeDesc::UINT32));
  }

  // Half RGBA and a float Z come out half and float again, by either path.
  void eachChannelKeepsItsStoredType_data() {
    QTest::addColumn<QStringList>("options");
    QTest::newRow("stored path") << QStringList{};
    QTest::newRow("linear float path") << QStringList{"--colourspace", "srgb"};
  }
  void eachChannelKeepsItsStoredType() {
    QFETCH(QStringList, options);
    OIIO::ImageSpec spec(kW, kH, 5, OIIO::TypeDesc::HALF);
    spec.channelnames = {"R", "G", "B", "A", "Z"};
    spec.alpha_channel = 3;
    spec.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF,
                           OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT};
    std::vector<float> pixels;
    for (int p = 0; p < kW * kH; ++p)
      for (float v : {0.25f, 0.5f, 0.75f, 1.0f, 1000.0f + static_cast<float>(p)})
        pixels.push_back(v);
    {
      auto out = OIIO::ImageOutput::create(path("mixed.exr").toStdString());
      QVERIFY(out && out->open(path("mixed.exr").toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    const QString out = path("mixed-out.exr");
    QFile::remove(out);
    const Run r = artcamCli(
        QStringList{"warp", path("mixed.exr"), path("h.artcam"), "-o", out, "-q"} + options);
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ReadBack back = readBack(out);
    QCOMPARE(back.spec.nchannels, 5);
    for (int c = 0; c < 4; ++c)
      QCOMPARE(back.spec.channelformat(c), OIIO::TypeDesc(OIIO::TypeDesc::HALF));
    QCOMPARE(back.spec.channelformat(4), OIIO::TypeDesc(OIIO::TypeDesc::FLOAT));
  }

  // A two-part EXR (colour, then a part of depth and an object ID) keeps both parts: the second
  // warped through the same camera, each channel at the nearest texel of the same source point,
  // its name, channel names and types kept.
  void everyPartIsWarped() {
    QVERIFY(writeTwoParts(path("two-part.exr")));
    const Run r = artcamCli(
        {"warp", path("two-part.exr"), path("h.artcam"), "-o", path("two-part-out.exr"), "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(!r.err.contains("left out"), qPrintable(r.err));
    auto in = OIIO::ImageInput::open(path("two-part-out.exr").toStdString());
    QVERIFY(in);
    QCOMPARE(in->spec().get_string_attribute("name"), std::string("beauty"));
    // The first part's colour (and the alpha a warp adds where pixels have no preimage).
    QCOMPARE(in->spec().channelnames.front(), std::string("R"));
    QVERIFY(in->seek_subimage(1, 0));
    const OIIO::ImageSpec second = in->spec();
    QCOMPARE(second.get_string_attribute("name"), std::string("depthpass"));
    QCOMPARE(second.channelnames, (std::vector<std::string>{"Z", "object.id"}));
    QCOMPARE(second.channelformat(0), OIIO::TypeDesc(OIIO::TypeDesc::FLOAT));
    QCOMPARE(second.width, kW);
    QVERIFY(!in->seek_subimage(2, 0));
    in->geterror();
    QVERIFY(in->seek_subimage(1, 0));
    std::vector<float> values(static_cast<size_t>(kW) * kH * 2);
    QVERIFY(in->read_image(1, 0, 0, 2, OIIO::TypeDesc::FLOAT, values.data()));
    const Eigen::Matrix3d source_from_target = targetFromSourcePx().inverse();
    int checked = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const Eigen::Vector3d s = source_from_target * Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
        const double sx = s.x() / s.z(), sy = s.y() / s.z();
        if (sx < 1.0 || sy < 1.0 || sx > kW - 1.0 || sy > kH - 1.0) continue;
        const double fx = sx - std::floor(sx), fy = sy - std::floor(sy);
        if (fx < 1e-3 || fx > 1 - 1e-3 || fy < 1e-3 || fy > 1 - 1e-3) continue;
        const int tx = static_cast<int>(std::floor(sx)), ty = static_cast<int>(std::floor(sy));
        const float* px = &values[(static_cast<size_t>(y) * kW + static_cast<size_t>(x)) * 2];
        QVERIFY2(px[0] == depthValue(tx, ty) && px[1] == objectId(tx, ty),
                 qPrintable(QString("output (%1, %2): Z %3 id %4, expected %5 and %6")
                                .arg(x)
                                .arg(y)
                                .arg(double(px[0]))
                                .arg(double(px[1]))
                                .arg(double(depthValue(tx, ty)))
                                .arg(double(objectId(tx, ty)))));
        ++checked;
      }
    QVERIFY2(checked > kW * kH / 2, qPrintable(QString::number(checked)));
  }

  // Into a format of one part, the later parts are not dropped silently: one warning line names
  // them and why, the first part written.
  void laterPartsAreNamedAsLeftOut() {
    QVERIFY(writeTwoParts(path("two-part.exr")));
    const Run r = artcamCli(
        {"warp", path("two-part.exr"), path("h.artcam"), "-o", path("two-part-out.png"), "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QStringList lines = r.err.trimmed().split('\n');
    int naming = 0;
    for (const QString& line : lines)
      if (line.contains("warning") && line.contains("\"depthpass\"") &&
          line.contains(path("two-part.exr")) && line.contains("left out"))
        ++naming;
    QVERIFY2(naming == 1, qPrintable(r.err));
    QVERIFY(QFile::exists(path("two-part-out.png")));
  }

  // Overscan: a data window beyond the display window is kept. The output has both windows of
  // the input, and each of its data-window pixels holds the input's colour at the source point
  // of its display-window position (the colour is linear in position, so bilinear is exact).
  void overscanIsKeptAsADataWindow() {
    constexpr int kOx = -8, kOy = -6, kDw = kW + 16, kDh = kH + 12;
    OIIO::ImageSpec spec(kDw, kDh, 3, OIIO::TypeDesc::FLOAT);
    spec.x = kOx;
    spec.y = kOy;
    spec.full_x = spec.full_y = 0;
    spec.full_width = kW;
    spec.full_height = kH;
    std::vector<float> pixels;
    for (int y = 0; y < kDh; ++y)
      for (int x = 0; x < kDw; ++x)
        for (float v : {(x + kOx + 0.5f) / kW, (y + kOy + 0.5f) / kH, 0.5f}) pixels.push_back(v);
    const std::string file = path("overscan.exr").toStdString();
    {
      auto out = OIIO::ImageOutput::create(file);
      QVERIFY(out && out->open(file, spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    const Run r = artcamCli(
        {"warp", path("overscan.exr"), path("h.artcam"), "-o", path("overscan-out.exr"), "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ReadBack back = readBack(path("overscan-out.exr"));
    QVERIFY(!back.pixels.empty());
    QCOMPARE(back.spec.x, kOx);
    QCOMPARE(back.spec.y, kOy);
    QCOMPARE(back.spec.width, kDw);
    QCOMPARE(back.spec.height, kDh);
    QCOMPARE(back.spec.full_x, 0);
    QCOMPARE(back.spec.full_y, 0);
    QCOMPARE(back.spec.full_width, kW);
    QCOMPARE(back.spec.full_height, kH);
    const Eigen::Matrix3d source_from_target = targetFromSourcePx().inverse();
    const size_t n = static_cast<size_t>(back.spec.nchannels);
    int checked = 0, outside_display = 0;
    for (int y = 0; y < kDh; ++y)
      for (int x = 0; x < kDw; ++x) {
        const double tx = x + kOx + 0.5, ty = y + kOy + 0.5;  // display-window position
        const Eigen::Vector3d s = source_from_target * Eigen::Vector3d(tx, ty, 1.0);
        const double sx = s.x() / s.z(), sy = s.y() / s.z();
        // A texel's margin inside the data window: every bilinear tap is a real texel.
        if (sx < kOx + 1.0 || sy < kOy + 1.0 || sx > kOx + kDw - 1.0 || sy > kOy + kDh - 1.0)
          continue;
        const float* px = &back.pixels[(static_cast<size_t>(y) * kDw + static_cast<size_t>(x)) * n];
        QVERIFY2(std::abs(px[0] - sx / kW) < 1e-4 && std::abs(px[1] - sy / kH) < 1e-4,
                 qPrintable(QString("data pixel (%1, %2): %3, %4; expected %5, %6")
                                .arg(x)
                                .arg(y)
                                .arg(double(px[0]))
                                .arg(double(px[1]))
                                .arg(sx / kW)
                                .arg(sy / kH)));
        if (tx < 0 || ty < 0 || tx > kW || ty > kH) ++outside_display;
        ++checked;
      }
    QVERIFY2(checked > kW * kH / 2 && outside_display > 100,
             qPrintable(QString("%1 checked, %2 outside the display window")
                            .arg(checked)
                            .arg(outside_display)));
  }
};

QTEST_GUILESS_MAIN(TestCliExrParts)
#include "test_cli_exr_parts.moc"
