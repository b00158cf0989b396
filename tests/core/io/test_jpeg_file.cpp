// SPDX-License-Identifier: Apache-2.0
// JPEG files without the OpenImageIO module (core/io/jpeg_file.h) against the module's own
// readers and stored-type writer (oiio_io.h, called directly): the same samples and floats, the
// same ImageInfo but the spec, and written files that decode to the same pixels and carry the same
// ICC profile, comment, orientation and quality. Files it does not take come back nullopt.
// Fixtures are written here with OpenImageIO and exiv2 directly.
#include "core/io/jpeg_file.h"
#include "core/io/oiio_io.h"
#include "tests/support/icc_files.h"
#include "tests/support/photo_files.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

using namespace artcam;
using namespace artcam::test;

namespace {

// Edges and noise, so any difference in the coding shows in the decoded pixels.
OIIO::ImageBuf texture(int width, int height, int channels) {
  OIIO::ImageBuf image(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8));
  std::uint32_t seed = 987;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float px[3];
      for (int c = 0; c < channels; ++c) {
        seed = seed * 1664525u + 1013904223u;
        px[c] = ((x / 8 + y / 8) % 2 ? 0.65f : 0.25f) + 0.3f * static_cast<float>(seed >> 24) / 255.0f;
      }
      image.setpixel(x, y, px, channels);
    }
  return image;
}

// A camera-like JPEG: stored turned (EXIF Orientation `o`), a comment, optionally a profile.
bool writePhoto(const std::string& path, const OIIO::ImageBuf& stored, int o, int quality,
                const std::vector<unsigned char>* icc) {
  OIIO::ImageSpec spec = stored.spec();
  spec.attribute("Orientation", o);
  spec.attribute("ImageDescription", "a test photo");
  spec.attribute("CompressionQuality", quality);
  spec.attribute("Compression", "jpeg:" + std::to_string(quality));
  if (icc) setProfile(spec, *icc);
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec)) return false;
  std::vector<std::uint8_t> bytes(spec.image_bytes());
  stored.get_pixels(stored.roi(), OIIO::TypeDesc::UINT8, bytes.data());
  return out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) && out->close();
}

struct Decoded {
  OIIO::ImageSpec spec;
  std::vector<std::uint8_t> bytes;
};
Decoded decode(const std::string& path) {
  Decoded d;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return d;
  d.spec = in->spec();
  d.bytes.resize(d.spec.image_bytes());
  if (!in->read_image(0, 0, 0, d.spec.nchannels, OIIO::TypeDesc::UINT8, d.bytes.data())) d.bytes.clear();
  return d;
}

std::vector<std::uint8_t> bytesOf(const StoredImage& image) {
  const size_t n = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
                   static_cast<size_t>(image.channels);
  return {image.bytes.data(), image.bytes.data() + n};
}

}  // namespace

class TestJpegFile : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const std::string& name) const {
    return dir_.filePath(QString::fromStdString(name)).toStdString();
  }

 private slots:
  void readsAsTheModuleReads_data() {
    QTest::addColumn<int>("channels");
    QTest::addColumn<int>("orientation");
    QTest::addColumn<bool>("profile");
    QTest::newRow("rgb upright") << 3 << 1 << false;
    QTest::newRow("rgb turned, Adobe RGB") << 3 << 6 << true;
    QTest::newRow("rgb mirrored") << 3 << 2 << false;
    QTest::newRow("grey turned") << 1 << 8 << false;
  }
  void readsAsTheModuleReads() {
    QFETCH(int, channels);
    QFETCH(int, orientation);
    QFETCH(bool, profile);
    const std::string file = path("in.jpg");
    const std::vector<unsigned char> adobe = adobeRgbProfile();
    QVERIFY(writePhoto(file, texture(203, 117, channels), orientation, 87, profile ? &adobe : nullptr));

    const auto shape = jpeg_file::readShape(file);
    QVERIFY(shape.has_value());
    QVERIFY2(*shape, shape->status.message.c_str());
    const auto module_shape = oiio_io::readStoredShape(file);
    QVERIFY(module_shape);
    QCOMPARE((*shape)->width, module_shape->width);
    QCOMPARE((*shape)->height, module_shape->height);
    QCOMPARE((*shape)->channels, module_shape->channels);

    const auto ours = jpeg_file::readStored(file, {});
    QVERIFY(ours.has_value());
    QVERIFY2(*ours, ours->status.message.c_str());
    const auto theirs = oiio_io::readStoredImage(file, {});
    QVERIFY2(theirs, theirs.status.message.c_str());
    const StoredImage& a = **ours;
    const StoredImage& b = *theirs;
    QCOMPARE(a.width, b.width);
    QCOMPARE(a.height, b.height);
    QCOMPARE(a.channels, b.channels);
    QCOMPARE(a.alpha_channel, b.alpha_channel);
    QVERIFY(bytesOf(a) == bytesOf(b));
    QCOMPARE(a.info.format_name, b.info.format_name);
    QCOMPARE(a.info.pixel_type, b.info.pixel_type);
    QCOMPARE(a.info.srgb, b.info.srgb);
    QCOMPARE(a.info.colour_space, b.info.colour_space);
    QCOMPARE(a.info.stored_orientation, orientation);
    QCOMPARE(b.info.stored_orientation, orientation);
    QCOMPARE(a.info.jpeg_quality, b.info.jpeg_quality);
    QCOMPARE(a.info.metadata != nullptr, b.info.metadata != nullptr);
    QVERIFY(a.info.dropped_channels.empty());
    QVERIFY(!a.info.spec);  // read without OpenImageIO

    // As linear float (readImage): the same floats; a profile to convert through is the
    // module's (lcms2), so this path declines it.
    const auto floats = jpeg_file::readFloat(file, {});
    if (profile) {
      QVERIFY(!floats.has_value());
      return;
    }
    QVERIFY(floats.has_value());
    QVERIFY2(*floats, floats->status.message.c_str());
    const auto module_floats = oiio_io::readImage(file, {});
    QVERIFY2(module_floats, module_floats.status.message.c_str());
    const ImageF& f = (*floats)->image;
    const ImageF& g = module_floats->image;
    QCOMPARE(f.width, g.width);
    QCOMPARE(f.height, g.height);
    QCOMPARE(f.channels, g.channels);
    QCOMPARE(f.alpha_channel, g.alpha_channel);
    QVERIFY(f.data == g.data);
    QCOMPARE((*floats)->info.colour_space, module_floats->info.colour_space);
    QCOMPARE((*floats)->info.srgb, module_floats->info.srgb);
    QCOMPARE((*floats)->info.stored_orientation, module_floats->info.stored_orientation);
    QCOMPARE((*floats)->info.jpeg_quality, module_floats->info.jpeg_quality);
    QVERIFY(!(*floats)->info.icc && !module_floats->info.icc);
  }

  // The same photo written by both writers from what each reader gave: the same coded pixels
  // and the same carried header (profile, comment, upright orientation, quality).
  void writesAsTheModuleWrites() {
    const std::string file = path("photo.jpg");
    const std::vector<unsigned char> adobe = adobeRgbProfile();
    QVERIFY(writePhoto(file, texture(190, 141, 3), 6, 83, &adobe));
    const auto ours = jpeg_file::readStored(file, {});
    QVERIFY(ours && *ours);
    const auto theirs = oiio_io::readStoredImage(file, {});
    QVERIFY(theirs);
    const StoredImage& image = **ours;

    const std::string native = path("native.jpg"), module = path("module.jpg");
    const auto whole = [&image](int y0, int y1, ConstImageView& rows) {
      rows = image.view();
      rows.data = image.view().row(y0);
      rows.height = y1 - y0;
      return Status::success();
    };
    const auto written = jpeg_file::writeBands(native, image.view(), &image.info, {}, whole);
    QVERIFY(written.has_value());
    QVERIFY2(*written, written->message.c_str());
    const Status s = oiio_io::writeStoredImage(module, theirs->view(), &theirs->info, {});
    QVERIFY2(s, s.message.c_str());

    const Decoded a = decode(native), b = decode(module);
    QVERIFY(!a.bytes.empty() && !b.bytes.empty());
    QCOMPARE(a.spec.width, 141);  // upright: the stored raster was turned a quarter
    QCOMPARE(a.spec.height, 190);
    QCOMPARE(a.spec.nchannels, b.spec.nchannels);
    QVERIFY(a.bytes == b.bytes);
    QVERIFY(profileOf(a.spec) == adobe);
    QVERIFY(profileOf(b.spec) == adobe);
    QCOMPARE(a.spec.get_string_attribute("ImageDescription"), std::string("a test photo"));
    QCOMPARE(a.spec.get_int_attribute("Orientation", 1), 1);
    QCOMPARE(b.spec.get_int_attribute("Orientation", 1), 1);
    QCOMPARE(jpegQuantisationTables(native), jpegQuantisationTables(module));
  }

  void alphaIsDroppedAndGreyStaysGrey() {
    // RGBA → RGB (a JPEG has no alpha: the premultiplied colour is written), Y → Y.
    for (const int channels : {4, 1}) {
      const int w = 37, h = 29;
      StoredImage image = makeStoredImage(w, h, channels, channels == 4 ? 3 : -1, PixelType::UInt8);
      for (int i = 0; i < w * h * channels; ++i) image.bytes.data()[i] = static_cast<std::uint8_t>((i * 37) % 251);
      const std::string out = path(channels == 4 ? "rgba.jpg" : "grey.jpg");
      const Status s = writeStoredImage(out, std::as_const(image).view());
      QVERIFY2(s, s.message.c_str());
      const Decoded d = decode(out);
      QCOMPARE(d.spec.nchannels, channels == 4 ? 3 : 1);
      QCOMPARE(d.spec.width, w);
    }
  }

  void otherFilesGoToTheModule() {
    // A PNG is not read here; a JPEG with a .png name is (the bytes say what it is).
    const std::string png = path("flat.png");
    QVERIFY(texture(16, 16, 3).write(png));
    QVERIFY(!jpeg_file::readStored(png, {}).has_value());
    QVERIFY(!jpeg_file::readShape(png).has_value());
    const std::string disguised = path("really-a-jpeg.png");
    QVERIFY(writePhoto(path("renamed.jpg"), texture(16, 16, 3), 1, 90, nullptr));
    std::filesystem::rename(path("renamed.jpg"), disguised);
    QVERIFY(jpeg_file::readShape(disguised).has_value());
    // A missing file: the module's refusal (it names the file), not this path's.
    QVERIFY(!jpeg_file::readStored(path("missing.jpg"), {}).has_value());

    // Writes: another pixel type, another extension, a non-JPEG `like`.
    StoredImage image = makeStoredImage(8, 8, 3, -1, PixelType::UInt8);
    const auto rows = [&image](int y0, int y1, ConstImageView& v) {
      v = std::as_const(image).view();
      v.data = v.row(y0);
      v.height = y1 - y0;
      return Status::success();
    };
    QVERIFY(!jpeg_file::writeBands(path("x.png"), std::as_const(image).view(), nullptr, {}, rows).has_value());
    WriteImageOptions sixteen;
    sixteen.pixel_type = "uint16";
    QVERIFY(!jpeg_file::writeBands(path("x.jpg"), std::as_const(image).view(), nullptr, sixteen, rows).has_value());
    ImageInfo from_png;
    from_png.format_name = "png";
    QVERIFY(!jpeg_file::writeBands(path("x.jpg"), std::as_const(image).view(), &from_png, {}, rows).has_value());
    QVERIFY(jpeg_file::writeBands(path("x.jpg"), std::as_const(image).view(), nullptr, {}, rows).has_value());
  }

  void damageIsOneLine() {
    const std::string file = path("cut.jpg");
    QVERIFY(writePhoto(file, texture(120, 90, 3), 1, 90, nullptr));
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
    const auto read = jpeg_file::readStored(file, {});
    QVERIFY(read.has_value());
    QVERIFY(!*read);
    const std::string& message = read->status.message;
    QVERIFY2(message.rfind(file + ": cannot read: ", 0) == 0, message.c_str());
    QVERIFY(message.find('\n') == std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestJpegFile)
#include "test_jpeg_file.moc"
