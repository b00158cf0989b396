// SPDX-License-Identifier: Apache-2.0
// Images: round trips through PNG 8-bit, TIFF 16-bit and EXR float; sRGB decoding against the
// formula; alpha premultiplied inside, unassociated in PNG; metadata carried over; refusals
// that name the file and leave nothing behind. Fixtures are written with OIIO directly.
#include "core/io/image_io.h"
#include "core/colour/transfer.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <fstream>

using namespace artcam;

namespace {

double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

template <class T>
bool writeRaw(const std::string& path, int w, int h, int c, OIIO::TypeDesc type,
              const std::vector<T>& data, const std::function<void(OIIO::ImageSpec&)>& tweak = {}) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) return false;
  OIIO::ImageSpec spec(w, h, c, type);
  if (tweak) tweak(spec);
  return out->open(path, spec) && out->write_image(type, data.data()) && out->close();
}

template <class T>
std::vector<T> readRaw(const std::string& path, OIIO::TypeDesc type,
                       OIIO::ImageSpec* spec_out = nullptr) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  if (spec_out) *spec_out = spec;
  std::vector<T> data(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, type, data.data());
  return data;
}

QStringList entries(const QTemporaryDir& dir) {
  return QDir(dir.path())
      .entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

}  // namespace

class TestImageIo : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) { return dir_.filePath(name).toStdString(); }

 private slots:
  void srgbDecodeMatchesTheFormula() {
    std::vector<std::uint8_t> ramp(256);
    for (int v = 0; v < 256; ++v) ramp[v] = static_cast<std::uint8_t>(v);
    QVERIFY(writeRaw(path("ramp.png"), 256, 1, 1, OIIO::TypeDesc::UINT8, ramp));
    const auto loaded = readImage(path("ramp.png"));
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->image.channels, 1);
    QVERIFY(loaded->info.srgb);
    QCOMPARE(loaded->info.pixel_type, std::string("uint8"));
    QCOMPARE(loaded->info.format_name, std::string("png"));
    for (int v = 0; v < 256; ++v)
      QCOMPARE(loaded->image.data[v], static_cast<float>(srgbToLinear(v / 255.0)));
    // And the encoder is its inverse to well within a quantisation step.
    for (int v = 0; v <= 1000; ++v)
      QVERIFY(std::abs(Transfer::srgb().encode(srgbToLinear(v / 1000.0)) - v / 1000.0) < 1e-12);
  }

  void png8RoundTripIsExact() {
    const int w = 37, h = 23;
    std::vector<std::uint8_t> pixels(w * h * 3);
    for (auto& p : pixels) p = static_cast<std::uint8_t>(test::rng()() & 0xff);
    QVERIFY(writeRaw(path("in.png"), w, h, 3, OIIO::TypeDesc::UINT8, pixels));
    const auto loaded = readImage(path("in.png"));
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->image.width, w);
    QCOMPARE(loaded->image.alpha_channel, -1);
    const Status written = writeImage(path("out.png"), loaded->image, &loaded->info);
    QVERIFY2(written.ok, written.message.c_str());
    OIIO::ImageSpec spec;
    QVERIFY(readRaw<std::uint8_t>(path("out.png"), OIIO::TypeDesc::UINT8, &spec) == pixels);
    QCOMPARE(spec.format, OIIO::TypeDesc(OIIO::TypeDesc::UINT8));
  }

  void tiff16RoundTripIsExact() {
    const int w = 19, h = 11;
    std::vector<std::uint16_t> pixels(w * h * 3);
    for (auto& p : pixels) p = static_cast<std::uint16_t>(test::rng()() & 0xffff);
    QVERIFY(writeRaw(path("in.tif"), w, h, 3, OIIO::TypeDesc::UINT16, pixels));
    const auto loaded = readImage(path("in.tif"));
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->info.pixel_type, std::string("uint16"));
    QVERIFY(loaded->info.srgb);  // untagged 16-bit is taken as sRGB
    QCOMPARE(loaded->image.data[5], static_cast<float>(srgbToLinear(pixels[5] / 65535.0)));
    QVERIFY(writeImage(path("out.tif"), loaded->image, &loaded->info).ok);
    OIIO::ImageSpec spec;
    QVERIFY(readRaw<std::uint16_t>(path("out.tif"), OIIO::TypeDesc::UINT16, &spec) == pixels);
    QCOMPARE(spec.format, OIIO::TypeDesc(OIIO::TypeDesc::UINT16));
  }

  void exrRoundTripKeepsLinearValues() {
    ImageF image(16, 9, 3);
    for (float& v : image.data) v = static_cast<float>(test::uniform(-0.5, 40.0));
    WriteImageOptions as_float;
    as_float.pixel_type = "float";
    QVERIFY(writeImage(path("f.exr"), image, nullptr, as_float).ok);
    const auto exact = readImage(path("f.exr"));
    QVERIFY2(exact.ok(), exact.status.message.c_str());
    QVERIFY(!exact->info.srgb);
    QCOMPARE(exact->info.pixel_type, std::string("float"));
    QVERIFY(exact->image.data == image.data);

    QVERIFY(writeImage(path("h.exr"), image).ok);  // EXR's natural type is half
    const auto half = readImage(path("h.exr"));
    QVERIFY(half.ok());
    QCOMPARE(half->info.pixel_type, std::string("half"));
    for (size_t k = 0; k < image.data.size(); ++k)
      QVERIFY(std::abs(half->image.data[k] - image.data[k]) <=
              1e-3f * std::abs(image.data[k]) + 1e-6f);
  }

  void pngAlphaIsPremultipliedInsideAndUnassociatedOutside() {
    // Unassociated RGBA: a half-covered orange, an invisible white, an opaque grey.
    const std::vector<std::uint8_t> pixels{200, 100, 50, 128, 255, 255, 255, 0, 90, 90, 90, 255};
    QVERIFY(writeRaw(path("a.png"), 3, 1, 4, OIIO::TypeDesc::UINT8, pixels,
                     [](OIIO::ImageSpec& s) { s.attribute("oiio:UnassociatedAlpha", 1); }));
    const auto loaded = readImage(path("a.png"));
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->image.alpha_channel, 3);
    const float* p = loaded->image.pixel(0, 0);
    QCOMPARE(p[3], 128.0f / 255.0f);
    QVERIFY(std::abs(p[0] - srgbToLinear(200 / 255.0) * 128.0 / 255.0) < 1e-6);
    QCOMPARE(loaded->image.pixel(1, 0)[0], 0.0f);  // alpha 0: no colour inside
    QVERIFY(writeImage(path("a_out.png"), loaded->image, &loaded->info).ok);
    std::vector<std::uint8_t> expected = pixels;
    expected[4] = expected[5] = expected[6] = 0;  // alpha 0 -> colour 0 on write
    QVERIFY(readRaw<std::uint8_t>(path("a_out.png"), OIIO::TypeDesc::UINT8) == expected);

    // Gray + alpha survives too.
    ImageF ya(2, 1, 2, 1);
    ya.data = {0.25f, 0.5f, 0.0f, 0.0f};
    QVERIFY(writeImage(path("ya.png"), ya).ok);
    const auto ya_read = readImage(path("ya.png"));
    QVERIFY(ya_read.ok() && ya_read->image.channels == 2 && ya_read->image.alpha_channel == 1);
    QVERIFY(std::abs(ya_read->image.data[0] - 0.25f) < 0.005f);  // colour and alpha quantised
  }

  void exrAlphaStaysPremultiplied() {
    ImageF image(2, 1, 4, 3);
    image.data = {0.2f, 0.1f, 0.05f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f};
    QVERIFY(writeImage(path("a.exr"), image, nullptr, {"float", 95}).ok);
    QVERIFY(readRaw<float>(path("a.exr"), OIIO::TypeDesc::FLOAT) == image.data);
    const auto loaded = readImage(path("a.exr"));
    QVERIFY(loaded.ok() && loaded->image.data == image.data);
  }

  void jpegWithoutAlphaIsCompositedOverBlack() {
    ImageF image(8, 8, 4, 3);
    for (size_t k = 0; k < image.data.size(); k += 4)
      image.data[k] = 0.5f, image.data[k + 3] = 0.5f;
    QVERIFY(writeImage(path("c.jpg"), image).ok);
    const auto loaded = readImage(path("c.jpg"));
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->image.channels, 3);
    QVERIFY(std::abs(loaded->image.data[0] - 0.5f) < 0.03f);
  }

  void metadataIsCarriedOver() {
    std::vector<std::uint8_t> pixels(4 * 4 * 3, 128);
    QVERIFY(
        writeRaw(path("meta.tif"), 4, 4, 3, OIIO::TypeDesc::UINT8, pixels, [](OIIO::ImageSpec& s) {
          s.attribute("ImageDescription", "a lens that expands red");
          s.attribute("Artist", "ARTcam tests");
          s.attribute("tiff:RowsPerStrip", 1);
        }));
    const auto loaded = readImage(path("meta.tif"));
    QVERIFY(loaded.ok());
    QVERIFY(writeImage(path("meta_out.png"), loaded->image, &loaded->info).ok);
    OIIO::ImageSpec spec;
    readRaw<std::uint8_t>(path("meta_out.png"), OIIO::TypeDesc::UINT8, &spec);
    QCOMPARE(QString::fromStdString(spec.get_string_attribute("ImageDescription")),
             QString("a lens that expands red"));
    QCOMPARE(QString::fromStdString(spec.get_string_attribute("Artist")), QString("ARTcam tests"));

    // A custom attribute in an EXR travels to the written EXR.
    std::vector<float> linear(4 * 4 * 3, 0.25f);
    QVERIFY(writeRaw(path("meta.exr"), 4, 4, 3, OIIO::TypeDesc::FLOAT, linear,
                     [](OIIO::ImageSpec& s) { s.attribute("artcamNote", "shot on a pinhole"); }));
    const auto exr = readImage(path("meta.exr"));
    QVERIFY(exr.ok());
    QVERIFY(writeImage(path("meta_out.exr"), exr->image, &exr->info).ok);
    readRaw<float>(path("meta_out.exr"), OIIO::TypeDesc::FLOAT, &spec);
    QCOMPARE(QString::fromStdString(spec.get_string_attribute("artcamNote")),
             QString("shot on a pinhole"));
    QCOMPARE(spec.format, OIIO::TypeDesc(OIIO::TypeDesc::FLOAT));  // like's pixel type kept
  }

  void readRefusalsNameTheFile() {
    const auto missing = readImage(path("photo.jpg"));
    QVERIFY(!missing.ok());
    QCOMPARE(missing.status.message, path("photo.jpg") + ": cannot read: no such file");
    std::ofstream(path("junk.jpg")) << "this is not a JPEG\nat all\n";
    const auto junk = readImage(path("junk.jpg"));
    QVERIFY(!junk.ok());
    QVERIFY2(junk.status.message.rfind(path("junk.jpg") + ": cannot read: ", 0) == 0,
             junk.status.message.c_str());
    QVERIFY(junk.status.message.find('\n') == std::string::npos);
  }

  void progressIsReportedAndCancels() {
    ImageF image(64, 256, 3);
    QVERIFY(writeImage(path("big.png"), image).ok);
    std::vector<double> seen;
    ReadImageOptions options;
    options.progress = [&](double f) {
      seen.push_back(f);
      return true;
    };
    QVERIFY(readImage(path("big.png"), options).ok());
    QVERIFY(!seen.empty() && seen.back() == 1.0);
    options.progress = [](double) { return false; };
    const auto cancelled = readImage(path("big.png"), options);
    QVERIFY(!cancelled.ok());
    QCOMPARE(cancelled.status.message, path("big.png") + ": cannot read: cancelled");
  }

  void unknownExtensionIsRefusedAndLeavesNothing() {
    QTemporaryDir dir;
    const std::string target = dir.filePath("out.xyz").toStdString();
    const Status status = writeImage(target, ImageF(4, 4, 3));
    QVERIFY(!status.ok);
    QCOMPARE(status.message, target + ": no image format for extension \".xyz\"");
    QVERIFY(entries(dir).isEmpty());
  }

  void failedWriteLeavesThePreviousImage() {
    QTemporaryDir dir;
    const std::string target = dir.filePath("keep.png").toStdString();
    QVERIFY(writeImage(target, ImageF(4, 4, 3)).ok);
    const auto before = readRaw<std::uint8_t>(target, OIIO::TypeDesc::UINT8);
    QVERIFY(!before.empty());
    // Refused before anything is written.
    WriteImageOptions bad;
    bad.pixel_type = "int7";
    Status status = writeImage(target, ImageF(4, 4, 3), nullptr, bad);
    QVERIFY(!status.ok && status.message.find("unknown pixel type") != std::string::npos);
    // Refused by the format itself once the temporary exists: libpng stops at 1e6 pixels wide.
    status = writeImage(target, ImageF(1000001, 1, 3));
    QVERIFY(!status.ok);
    QVERIFY2(status.message.rfind(target + ": cannot write: ", 0) == 0, status.message.c_str());
    QVERIFY2(status.message.find(".tmp-") == std::string::npos, status.message.c_str());
    QVERIFY(readRaw<std::uint8_t>(target, OIIO::TypeDesc::UINT8) == before);
    QCOMPARE(entries(dir), QStringList{"keep.png"});
    // A JPEG too large for libjpeg is refused up front (libjpeg would exit() the process).
    status = writeImage(dir.filePath("wide.jpg").toStdString(), ImageF(70000, 1, 3));
    QVERIFY2(!status.ok && status.message.find("65500") != std::string::npos,
             status.message.c_str());
    QCOMPARE(entries(dir), QStringList{"keep.png"});
  }
};

QTEST_GUILESS_MAIN(TestImageIo)
#include "test_image_io.moc"
