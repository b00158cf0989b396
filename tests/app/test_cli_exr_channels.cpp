// SPDX-License-Identifier: Apache-2.0
// A multi-channel OpenEXR through artcam warp and batch: every channel beyond RGBA (depth,
// normals, AOV colour) is warped through the same camera at the same source positions, its name
// kept; depth takes the nearest texel; the display window is kept and the data window with it.
//
// The input's extra channels hold their own texel coordinates (channel e: e + x/64 or e + y/64),
// so bilinear resampling of them is exact: at source point (sx, sy) the value is
// e + (sx - 0.5)/64 (pixel centres at i + 0.5). Z holds the texel's index 1 + x + 64 y, so only
// the nearest texel's own value passes. The source point of each output pixel is computed here
// from the homography's pixel matrix, not by the code under test.
#include "tests/app/cli_run.h"
#include "tests/support/exr_files.h"

#include "core/io/artcam_file.h"
#include "core/model/camera.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <OpenImageIO/imageio.h>

#include <Eigen/Dense>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <string>
#include <vector>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 64, kH = 48;
constexpr int kOriginX = 5, kOriginY = 7;  // the display window's origin (data window the same)
const std::vector<std::string> kNames = {"R",   "G",   "B",   "A",         "Z",
                                         "N.x", "N.y", "N.z", "diffuse.R", "diffuse.G"};
constexpr int kFirstExtra = 4;

// Target pixel = H source pixel (pixel coordinates of the 64x48 display window).
Eigen::Matrix3d targetFromSourcePx() {
  Eigen::Matrix3d h;
  h << 1.05, 0.03, -2.3,  //
      0.02, 0.97, 1.7,    //
      1.0e-4, -2.0e-4, 1.0;
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

// Extra channel e (0 for Z): its value at texel (x, y).
float extraValue(int e, int x, int y) {
  if (e == 0) return static_cast<float>(1 + x + kW * y);
  return static_cast<float>(e) + static_cast<float>(e % 2 == 1 ? x : y) / 64.0f;
}

bool writeInput(const QString& path) {
  const float colour[4] = {0.25f, 0.5f, 0.75f, 1.0f};
  return artcam::test::writeFloatExr(path.toStdString(), kW, kH, kNames, 3, kOriginX, kOriginY,
                       [&colour](int c, int x, int y) {
                         return c < kFirstExtra ? colour[c] : extraValue(c - kFirstExtra, x, y);
                       });
}

struct ReadBack {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
};
ReadBack readBack(const QString& path) {
  ReadBack r;
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return r;
  r.spec = in->spec();
  r.pixels.resize(static_cast<size_t>(r.spec.image_pixels()) *
                  static_cast<size_t>(r.spec.nchannels));
  if (!in->read_image(0, 0, 0, r.spec.nchannels, OIIO::TypeDesc::FLOAT, r.pixels.data()))
    r.pixels.clear();
  return r;
}

// Every extra channel of `path` against its value at the independent source point; returns the
// number of pixels checked (those whose bilinear footprint lies inside the source), or -1 after
// a failed check (reported by QVERIFY2 through `failure`).
int checkWarpedChannels(const QString& path, QString& failure) {
  const ReadBack out = readBack(path);
  if (out.pixels.empty()) {
    failure = path + ": cannot read back";
    return -1;
  }
  if (out.spec.channelnames != kNames) {
    failure = "channel names differ: " + QString::fromStdString(OIIO::Strutil::join(out.spec.channelnames, ","));
    return -1;
  }
  if (out.spec.x != kOriginX || out.spec.y != kOriginY || out.spec.full_x != kOriginX ||
      out.spec.full_y != kOriginY || out.spec.full_width != kW || out.spec.full_height != kH ||
      out.spec.width != kW || out.spec.height != kH) {
    failure = QString("windows not kept: data %1,%2 %3x%4, display %5,%6 %7x%8")
                  .arg(out.spec.x).arg(out.spec.y).arg(out.spec.width).arg(out.spec.height)
                  .arg(out.spec.full_x).arg(out.spec.full_y).arg(out.spec.full_width)
                  .arg(out.spec.full_height);
    return -1;
  }
  const Eigen::Matrix3d source_from_target = targetFromSourcePx().inverse();
  const int n = out.spec.nchannels;
  int checked = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Eigen::Vector3d s = source_from_target * Eigen::Vector3d(x + 0.5, y + 0.5, 1.0);
      const double sx = s.x() / s.z(), sy = s.y() / s.z();
      // Inside the source by a texel's margin: all four bilinear taps are real texels.
      if (sx < 1.0 || sy < 1.0 || sx > kW - 1.0 || sy > kH - 1.0) continue;
      const float* px = &out.pixels[(static_cast<size_t>(y) * kW + static_cast<size_t>(x)) *
                                    static_cast<size_t>(n)];
      for (int e = 0; e < n - kFirstExtra; ++e) {
        const float got = px[kFirstExtra + e];
        double want = 0.0;
        if (e == 0) {
          // Nearest: the texel containing the source point; skip points on a texel border.
          const double fx = sx - std::floor(sx), fy = sy - std::floor(sy);
          if (fx < 1e-3 || fx > 1 - 1e-3 || fy < 1e-3 || fy > 1 - 1e-3) continue;
          want = extraValue(0, static_cast<int>(std::floor(sx)), static_cast<int>(std::floor(sy)));
        } else {
          want = e + ((e % 2 == 1 ? sx : sy) - 0.5) / 64.0;
        }
        // 1e-4 of a value is 0.0064 of a texel.
        if (std::abs(got - want) > (e == 0 ? 0.0 : 1e-4)) {
          failure = QString("%1 at output (%2, %3), source (%4, %5): %6, expected %7")
                        .arg(QString::fromStdString(kNames[static_cast<size_t>(kFirstExtra + e)]))
                        .arg(x).arg(y).arg(sx).arg(sy).arg(static_cast<double>(got)).arg(want);
          for (int c = 0; c < n; ++c) failure += " " + QString::number(static_cast<double>(px[c]));
          return -1;
        }
      }
      ++checked;
    }
  return checked;
}

}  // namespace

class TestCliExrChannels : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeHomographyCamera(path("h.artcam")));
    QVERIFY(writeInput(path("aov.exr")));
  }

  void everyChannelIsWarpedAtTheSameSourcePoint_data() {
    QTest::addColumn<QStringList>("options");
    QTest::newRow("stored float path") << QStringList{};
    // --colourspace srgb takes the linear float path (warp_job.h); float output stays linear.
    QTest::newRow("linear float path") << QStringList{"--colourspace", "srgb"};
  }
  void everyChannelIsWarpedAtTheSameSourcePoint() {
    QFETCH(QStringList, options);
    const QString out = path(QString("out-%1.exr").arg(options.size()));
    const Run r = artcamCli(QStringList{"warp", path("aov.exr"), path("h.artcam"), "-o", out,
                                        "--json", "-q", "--overwrite"} + options);
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(!r.err.contains("left out"), qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["extra_channels"].toArray(),
             QJsonArray({"Z", "N.x", "N.y", "N.z", "diffuse.R", "diffuse.G"}));
    QVERIFY(!j.contains("dropped_channels"));
    QString failure;
    const int checked = checkWarpedChannels(out, failure);
    QVERIFY2(checked >= 0, qPrintable(failure));
    QVERIFY2(checked > kW * kH / 2, qPrintable(QString::number(checked)));
  }

  void batchWarpsTheChannelsToo() {
    const Run r = artcamCli({"batch", path("h.artcam"), path("aov.exr"), "-o", path("batch"), "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QString failure;
    const int checked = checkWarpedChannels(path("batch/aov.exr"), failure);
    QVERIFY2(checked >= 0, qPrintable(failure));
    QVERIFY(checked > kW * kH / 2);
  }

  void aFormatWithoutExtraChannelsSaysTheyAreLeftOut() {
    const Run r = artcamCli({"warp", path("aov.exr"), path("h.artcam"), "-o", path("out.tif"),
                             "--json", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("aov.exr: channels beyond colour and alpha (Z, N.x, N.y, N.z, "
                            "diffuse.R, diffuse.G) are not warped and are left out of") &&
                 r.err.contains("out.tif: its format holds no channels beyond RGBA"),
             qPrintable(r.err));
    QCOMPARE(QJsonDocument::fromJson(r.out.toUtf8()).object()["dropped_channels"].toArray().size(), 6);
    QCOMPARE(readBack(path("out.tif")).spec.nchannels, 4);
  }

  void aCameraThatCannotMoveDataChannelsLeavesThemOutAndSaysWhy() {
    // Chromatic aberration moves R, G and B apart: an extra channel has no one source point.
    QCOMPARE(artcamCli({"preset", "chromatic-aberration", "--size", "64x48", "-o",
                        path("ca.artcam")}).exit_code, 0);
    const Run r = artcamCli({"warp", path("aov.exr"), path("ca.artcam"), "-o", path("ca.exr"), "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("are not warped and are left out of") &&
                 r.err.contains("chromatic aberration"),
             qPrintable(r.err));
    QCOMPARE(readBack(path("ca.exr")).spec.nchannels, 4);
  }

  void aDataWindowThatIsNotTheDisplayWindowIsKept() {
    const QString file = path("cropped.exr");
    {
      OIIO::ImageSpec spec(32, 24, 3, OIIO::TypeDesc::FLOAT);
      spec.x = 8;
      spec.y = 4;
      spec.full_x = spec.full_y = 0;
      spec.full_width = kW;
      spec.full_height = kH;
      const std::vector<float> pixels(32 * 24 * 3, 0.5f);
      auto out = OIIO::ImageOutput::create(file.toStdString());
      QVERIFY(out && out->open(file.toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    const Run r = artcamCli({"warp", file, path("h.artcam"), "-o", path("cropped-out.exr"), "-q"});
    // The crop's pixels stay where they lie in the frame: the output has the same windows.
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ReadBack back = readBack(path("cropped-out.exr"));
    QCOMPARE(back.spec.x, 8);
    QCOMPARE(back.spec.y, 4);
    QCOMPARE(back.spec.width, 32);
    QCOMPARE(back.spec.height, 24);
    QCOMPARE(back.spec.full_width, kW);
    QCOMPARE(back.spec.full_height, kH);
  }
};

QTEST_GUILESS_MAIN(TestCliExrChannels)
#include "test_cli_exr_channels.moc"
