// SPDX-License-Identifier: Apache-2.0
// Cameras know their frame (core/pipeline/camera_frame.h), end to end: a portrait JPEG as a
// camera writes it (a landscape sensor raster tagged EXIF Orientation 6) corrected by an
// `artcam lens camera` camera must equal correcting the untagged sensor raster, then turning it
// upright. The truth is made outside the code under test: the two JPEGs are one OpenImageIO
// encode with and without the tag, and the turn is OpenImageIO's ImageBufAlgo::rotate90 (the
// quarter turn clockwise that Orientation 6 asks of a viewer, EXIF 2.32 §4.6.4 tag 274).
#include "tests/app/cli_run.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <QtTest/QtTest>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>
#include <cstdlib>
#include <vector>

using artcam::test::artcamCli;

namespace {

constexpr int kW = 600, kH = 400;
const char* const kLens = "Canon PowerShot G11 & compatibles (Standard)";

// Detail at a few pixels and no symmetry: a camera stretched onto the wrong frame moves it a lot.
unsigned char pattern(int x, int y, int c) {
  const double v = 0.5 + 0.25 * std::sin(2 * M_PI * (x + 0.5) / (23.0 + 7 * c)) +
                   0.2 * std::cos(2 * M_PI * (y + 0.5) / 17.0) + 0.0006 * (x - y);
  return static_cast<unsigned char>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

// The landscape sensor raster as a JPEG, tagged `orientation` (0: no tag).
bool writeSensorJpeg(const std::string& path, int orientation) {
  std::vector<unsigned char> px(static_cast<size_t>(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) px[(static_cast<size_t>(y) * kW + x) * 3 + c] = pattern(x, y, c);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("CompressionQuality", 95);
  if (orientation) spec.attribute("Orientation", orientation);
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) &&
         out->close();
}

struct Pixels {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // 0..255
};

Pixels pixelsOf(const OIIO::ImageBuf& buf) {
  Pixels p;
  const OIIO::ImageSpec& spec = buf.spec();
  p.width = spec.width;
  p.height = spec.height;
  p.channels = spec.nchannels;
  p.data.resize(static_cast<size_t>(p.width) * p.height * p.channels);
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, p.data.data());
  for (float& v : p.data) v *= 255.0f;
  return p;
}

Pixels readPixels(const std::string& path) { return pixelsOf(OIIO::ImageBuf(path)); }

// The untagged sensor raster corrected, then turned as Orientation 6 shows it.
Pixels turnedQuarterClockwise(const std::string& path) {
  return pixelsOf(OIIO::ImageBufAlgo::rotate90(OIIO::ImageBuf(path)));
}

struct Difference {
  double mean = 0.0, max = 0.0;
};
Difference difference(const Pixels& a, const Pixels& b) {
  Difference d;
  const int channels = std::min(a.channels, b.channels);
  double sum = 0.0;
  const size_t pixels = static_cast<size_t>(a.width) * a.height;
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < channels; ++c) {
      const double e = std::abs(a.data[i * a.channels + c] - b.data[i * b.channels + c]);
      sum += e;
      d.max = std::max(d.max, e);
    }
  d.mean = sum / (static_cast<double>(pixels) * channels);
  return d;
}

QJsonObject json(const QString& text) { return QJsonDocument::fromJson(text.toUtf8()).object(); }

QByteArray readAll(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

bool writeAll(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}

}  // namespace

class TestCliCameraFrame : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(QString::fromLatin1(name)); }
  std::string spath(const char* name) const { return path(name).toStdString(); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeSensorJpeg(spath("sensor.jpg"), 0));
    QVERIFY(writeSensorJpeg(spath("portrait.jpg"), 6));
    // The tagged file reads upright, as any viewer shows it.
    const OIIO::ImageBuf shown(spath("portrait.jpg"));
    QCOMPARE(shown.spec().get_int_attribute("Orientation", 1), 6);
    const auto made = artcamCli({"lens", "camera", "--lens", kLens, "--focal", "6.1", "--size",
                                 "600x400", "-o", path("lens.artcam")});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
    // The truth: the sensor raster corrected, then turned.
    const auto r = artcamCli(
        {"warp", path("sensor.jpg"), path("lens.artcam"), "-o", path("sensor_fixed.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
  }

  // The lens camera says it was made for the sensor raster.
  void lensCameraRecordsSensorFrame() {
    const QJsonObject cam = QJsonDocument::fromJson(readAll(path("lens.artcam"))).object();
    QCOMPARE(cam["frame"].toString(), QStringLiteral("sensor"));
  }

  void warpCorrectsSensorThenTurns() {
    const auto r = artcamCli({"warp", path("portrait.jpg"), path("lens.artcam"), "-o",
                              path("portrait_fixed.png"), "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(!r.err.contains("aspect"), qPrintable(r.err));  // the frames match: no stretch
    const Pixels got = readPixels(spath("portrait_fixed.png"));
    const Pixels want = turnedQuarterClockwise(spath("sensor_fixed.png"));
    QCOMPARE(got.width, kH);
    QCOMPARE(got.height, kW);
    QCOMPARE(want.width, kH);
    const Difference d = difference(got, want);
    qInfo("warp, tagged vs corrected then turned: mean %.4f/255, max %.4f/255", d.mean, d.max);
    QVERIFY2(d.max <= 1.0, qPrintable(QString::number(d.max)));
    // Written upright: a viewer must not turn it again.
    const OIIO::ImageBuf written(spath("portrait_fixed.png"));
    QCOMPARE(written.spec().get_int_attribute("Orientation", 1), 1);
  }

  void batchCorrectsSensorThenTurns() {
    const auto r = artcamCli({"batch", path("lens.artcam"), path("portrait.jpg"), "-o",
                              path("batch"), "--format", "png", "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QJsonObject file = json(r.out)["files"].toArray().at(0).toObject();
    QCOMPARE(file["width"].toInt(), kH);
    QCOMPARE(file["height"].toInt(), kW);
    QVERIFY(!file.contains("warning"));
    const Difference d = difference(readPixels(dir_.filePath("batch/portrait.png").toStdString()),
                                    turnedQuarterClockwise(spath("sensor_fixed.png")));
    qInfo("batch, tagged vs corrected then turned: mean %.4f/255, max %.4f/255", d.mean, d.max);
    QVERIFY2(d.max <= 1.0, qPrintable(QString::number(d.max)));
  }

  // A file that does not say (older builds): a source frame of the stored raster's size and not
  // the upright one's is taken as the sensor's.
  void fileWithoutFrameTakesStoredRasterBySize() {
    QJsonObject cam = QJsonDocument::fromJson(readAll(path("lens.artcam"))).object();
    cam.remove("frame");
    QVERIFY(writeAll(path("old.artcam"), QJsonDocument(cam).toJson()));
    const auto r =
        artcamCli({"warp", path("portrait.jpg"), path("old.artcam"), "-o", path("old_fixed.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Difference d = difference(readPixels(spath("old_fixed.png")),
                                    turnedQuarterClockwise(spath("sensor_fixed.png")));
    QVERIFY2(d.max <= 1.0, qPrintable(QString::number(d.max)));
  }

  // "upright" is obeyed: the landscape camera is stretched onto the upright portrait, and both
  // warp and batch say so (batch in text and in its JSON, per file).
  void uprightFrameIsStretchedWithWarning() {
    QJsonObject cam = QJsonDocument::fromJson(readAll(path("lens.artcam"))).object();
    cam["frame"] = QStringLiteral("upright");
    QVERIFY(writeAll(path("upright.artcam"), QJsonDocument(cam).toJson()));
    const auto w = artcamCli(
        {"warp", path("portrait.jpg"), path("upright.artcam"), "-o", path("stretched.png")});
    QVERIFY2(w.exit_code == 0, qPrintable(w.err));
    QVERIFY2(w.err.contains("another aspect"), qPrintable(w.err));
    const auto text = artcamCli({"batch", path("upright.artcam"), path("portrait.jpg"), "-o",
                                 path("stretched_text"), "--format", "png"});
    QVERIFY2(text.exit_code == 0, qPrintable(text.err));
    QVERIFY2(text.err.contains("warning: " + path("portrait.jpg")) &&
                 text.err.contains("another aspect"),
             qPrintable(text.err));
    const auto j = artcamCli({"batch", path("upright.artcam"), path("portrait.jpg"), "-o",
                              path("stretched_json"), "--format", "png", "--json"});
    QVERIFY2(j.exit_code == 0, qPrintable(j.err));
    const QJsonObject file = json(j.out)["files"].toArray().at(0).toObject();
    QVERIFY2(file["warning"].toString().contains("another aspect"), qPrintable(j.out));
    // Stretched in the upright frame: far from the sensor-frame correction.
    const Difference d = difference(readPixels(spath("stretched.png")),
                                    turnedQuarterClockwise(spath("sensor_fixed.png")));
    qInfo("camera applied upright (stretched): mean %.2f/255, max %.0f/255", d.mean, d.max);
    QVERIFY(d.mean > 2.0);
  }

  void unknownFrameIsRefused() {
    QJsonObject cam = QJsonDocument::fromJson(readAll(path("lens.artcam"))).object();
    cam["frame"] = QStringLiteral("sideways");
    QVERIFY(writeAll(path("bad.artcam"), QJsonDocument(cam).toJson()));
    const auto r =
        artcamCli({"warp", path("portrait.jpg"), path("bad.artcam"), "-o", path("bad.png")});
    QVERIFY(r.exit_code != 0);
    QVERIFY2(r.err.contains("/frame") && r.err.contains("sideways"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("bad.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliCameraFrame)
#include "test_cli_camera_frame.moc"
