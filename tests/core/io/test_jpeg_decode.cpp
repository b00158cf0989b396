// SPDX-License-Identifier: Apache-2.0
// The JPEG codec path of the stored-type reader (core/io/jpeg_decode.h): its pixels against
// OpenImageIO's own decode of the same file (both run libjpeg-turbo with its defaults, so the
// bytes must be equal), EXIF orientation still applied, damage still one clear line, and the
// DCT-scaled decode against a box average of the full decode. The files are written here with
// OpenImageIO directly, never through the engine's writers.
#include "core/io/image_io.h"
#include "core/io/jpeg_decode.h"
#include "core/io/stored_image.h"
#include "tests/support/photo_files.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

using namespace artcam;
using namespace artcam::test;

namespace {

// Texture with edges and noise-like detail, so every DCT coefficient and the chroma
// upsampling matter: a decoder that differs anywhere shows it.
OIIO::ImageBuf texture(int width, int height, int channels) {
  OIIO::ImageBuf image(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8));
  std::uint32_t seed = 12345;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float px[3];
      for (int c = 0; c < channels; ++c) {
        seed = seed * 1664525u + 1013904223u;
        const float noise = static_cast<float>(seed >> 24) / 255.0f;
        const float wave = 0.5f + 0.4f * std::sin(0.07f * static_cast<float>(x * (c + 1)) +
                                                  0.05f * static_cast<float>(y));
        px[c] = ((x / 16 + y / 16) % 2 ? 0.7f : 0.3f) * wave + 0.2f * noise;
      }
      image.setpixel(x, y, px, channels);
    }
  return image;
}

bool writeJpeg(const std::string& path, const OIIO::ImageBuf& image, const char* subsampling,
               bool progressive) {
  OIIO::ImageSpec spec = image.spec();
  spec.attribute("Compression", "jpeg:90");
  if (subsampling) spec.attribute("jpeg:subsampling", subsampling);
  if (progressive) spec.attribute("jpeg:progressive", 1);
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec)) return false;
  std::vector<std::uint8_t> bytes(spec.image_bytes());
  image.get_pixels(image.roi(), OIIO::TypeDesc::UINT8, bytes.data());
  return out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) && out->close();
}

// OpenImageIO's decode of `path`, as stored (no orientation applied).
std::vector<std::uint8_t> oiioDecode(const std::string& path, int& width, int& height,
                                     int& channels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  width = spec.width, height = spec.height, channels = spec.nchannels;
  std::vector<std::uint8_t> bytes(spec.image_bytes());
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, bytes.data())) return {};
  return bytes;
}

std::vector<std::uint8_t> bytesOf(const StoredImage& image) {
  return {image.bytes.data(), image.bytes.data() + static_cast<size_t>(image.width) *
                                                       static_cast<size_t>(image.height) *
                                                       static_cast<size_t>(image.channels)};
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

class TestJpegDecode : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const std::string& name) const {
    return dir_.filePath(QString::fromStdString(name)).toStdString();
  }

 private slots:
  void pixelsEqualOpenImageIO_data() {
    QTest::addColumn<int>("channels");
    QTest::addColumn<QString>("subsampling");
    QTest::addColumn<bool>("progressive");
    QTest::newRow("rgb 4:2:0") << 3 << "4:2:0" << false;
    QTest::newRow("rgb 4:2:2") << 3 << "4:2:2" << false;
    QTest::newRow("rgb 4:4:4") << 3 << "4:4:4" << false;
    QTest::newRow("rgb progressive") << 3 << "4:2:0" << true;
    QTest::newRow("grey") << 1 << "" << false;
  }

  // Odd sizes, so partial MCUs at the right and bottom edges are decoded too.
  void pixelsEqualOpenImageIO() {
    QFETCH(int, channels);
    QFETCH(QString, subsampling);
    QFETCH(bool, progressive);
    const std::string file = path("t.jpg");
    const std::string sub = subsampling.toStdString();
    QVERIFY(writeJpeg(file, texture(257, 131, channels), sub.empty() ? nullptr : sub.c_str(),
                      progressive));
    // The codec path must be the one taken, or the comparison below proves nothing.
    auto decoder = JpegDecoder::open(file);
    QVERIFY2(decoder, decoder.status.message.c_str());
    QVERIFY((*decoder)->supported());
    QCOMPARE((*decoder)->channels(), channels);

    int w = 0, h = 0, c = 0;
    const std::vector<std::uint8_t> truth = oiioDecode(file, w, h, c);
    QVERIFY(!truth.empty());
    const auto read = readStoredImage(file);
    QVERIFY2(read, read.status.message.c_str());
    QCOMPARE(read->width, w);
    QCOMPARE(read->height, h);
    QCOMPARE(read->channels, c);
    QCOMPARE(read->type, PixelType::UInt8);
    QVERIFY(bytesOf(*read) == truth);

    // The decoder alone, into rows padded beyond the pixels: only the pixels are written.
    std::vector<std::uint8_t> padded(static_cast<size_t>(h) * (static_cast<size_t>(w * c) + 5),
                                     0xA5);
    QVERIFY((*decoder)->decode(padded.data(), static_cast<size_t>(w * c) + 5).ok);
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* row = padded.data() + static_cast<size_t>(y) * (static_cast<size_t>(w * c) + 5);
      QVERIFY(std::equal(row, row + w * c, truth.begin() + static_cast<std::ptrdiff_t>(y) * w * c));
      for (int k = 0; k < 5; ++k) QCOMPARE(row[w * c + k], std::uint8_t{0xA5});
    }
  }

  // The float reader (the studio, linear cameras) takes the same codec path: its linear values
  // equal those of a PNG holding OpenImageIO's decode of the JPEG (read through OpenImageIO).
  void floatReaderEqualsOpenImageIOsBytes() {
    const std::string file = path("f.jpg");
    QVERIFY(writeJpeg(file, texture(131, 77, 3), nullptr, false));
    int w = 0, h = 0, c = 0;
    const std::vector<std::uint8_t> truth = oiioDecode(file, w, h, c);
    OIIO::ImageSpec spec(w, h, c, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    const std::string png = path("f.png");
    auto out = OIIO::ImageOutput::create(png);
    QVERIFY(out && out->open(png, spec) && out->write_image(OIIO::TypeDesc::UINT8, truth.data()) &&
            out->close());
    const auto from_jpeg = readImage(file);
    const auto from_png = readImage(png);
    QVERIFY2(from_jpeg, from_jpeg.status.message.c_str());
    QVERIFY2(from_png, from_png.status.message.c_str());
    QCOMPARE(from_jpeg->image.channels, from_png->image.channels);
    QVERIFY(from_jpeg->image.data == from_png->image.data);
  }

  // EXIF orientation 6 (stored a quarter turn): read upright, equal to OpenImageIO's decode
  // turned by its own reorient (right for 6, tests/core/io/test_photo_orientation.cpp).
  void orientationIsHonoured() {
    const std::string file = path("six.jpg");
    QVERIFY(writeOriented(file, storedFor(texture(64, 40, 3), 6), 6, 92));
    OIIO::ImageBuf decoded(file);
    QVERIFY(decoded.read(0, 0, true, OIIO::TypeDesc::UINT8));
    decoded.specmod().attribute("Orientation", 6);
    const OIIO::ImageBuf upright = OIIO::ImageBufAlgo::reorient(decoded);
    std::vector<std::uint8_t> truth(upright.spec().image_bytes());
    upright.get_pixels(upright.roi(), OIIO::TypeDesc::UINT8, truth.data());

    const auto read = readStoredImage(file);
    QVERIFY2(read, read.status.message.c_str());
    QCOMPARE(read->width, 64);
    QCOMPARE(read->height, 40);
    QCOMPARE(read->info.stored_orientation, 6);
    QVERIFY(bytesOf(*read) == truth);
  }

  // Cut after the header: libjpeg would fill the rest with grey and only warn.
  void truncatedJpegIsOneClearLine() {
    const std::string whole = path("whole.jpg");
    QVERIFY(writeJpeg(whole, texture(300, 200, 3), nullptr, false));
    const std::string bytes = slurp(whole);
    const std::string cut = path("cut.jpg");
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    for (const std::string& m : {readStoredImage(cut).status.message, readImage(cut).status.message}) {
      QVERIFY2(m.rfind(cut + ": cannot read: ", 0) == 0, m.c_str());
      QVERIFY2(m.find('\n') == std::string::npos, m.c_str());
      QVERIFY2(m.find("Premature end of JPEG file") != std::string::npos, m.c_str());
    }
  }

  // Garbage in the entropy-coded data (the header intact): refused, one line, not grey pixels.
  void corruptJpegIsOneClearLine() {
    const std::string whole = path("whole.jpg");
    QVERIFY(writeJpeg(whole, texture(300, 200, 3), nullptr, false));
    std::string bytes = slurp(whole);
    for (size_t k = bytes.size() / 2; k < bytes.size() / 2 + 64; ++k) bytes[k] = '\xFF';
    const std::string bad = path("bad.jpg");
    std::ofstream(bad, std::ios::binary) << bytes;
    const auto read = readStoredImage(bad);
    QVERIFY(!read);
    QVERIFY2(read.status.message.rfind(bad + ": cannot read: ", 0) == 0,
             read.status.message.c_str());
    QVERIFY2(read.status.message.find('\n') == std::string::npos, read.status.message.c_str());
  }

  void cancelStopsTheDecode() {
    const std::string file = path("c.jpg");
    QVERIFY(writeJpeg(file, texture(200, 300, 3), nullptr, false));
    ReadImageOptions options;
    options.progress = [](double) { return false; };
    const auto read = readStoredImage(file, options);
    QVERIFY(!read);
    QCOMPARE(read.status.message, file + ": cannot read: cancelled");
  }

  // 1/2, 1/4, 1/8 of each side (rounded up), and close to the full decode averaged over the
  // same blocks: libjpeg's scaled IDCT is a different filter, so a bound, not equality.
  void scaledDecodeIsAReducedPhoto_data() {
    QTest::addColumn<int>("denominator");
    QTest::newRow("1/2") << 2;
    QTest::newRow("1/4") << 4;
    QTest::newRow("1/8") << 8;
  }

  void scaledDecodeIsAReducedPhoto() {
    QFETCH(int, denominator);
    const std::string file = path("s.jpg");
    // Smooth, so a block average is a fair truth for any reduction filter.
    OIIO::ImageBuf smooth(OIIO::ImageSpec(403, 301, 3, OIIO::TypeDesc::UINT8));
    for (int y = 0; y < 301; ++y)
      for (int x = 0; x < 403; ++x) {
        const float px[3] = {0.5f + 0.4f * std::sin(0.02f * static_cast<float>(x)),
                             0.5f + 0.4f * std::cos(0.03f * static_cast<float>(y)), 0.4f};
        smooth.setpixel(x, y, px, 3);
      }
    QVERIFY(writeJpeg(file, smooth, nullptr, false));
    int w = 0, h = 0, c = 0;
    const std::vector<std::uint8_t> full = oiioDecode(file, w, h, c);
    auto decoder = JpegDecoder::open(file, denominator);
    QVERIFY2(decoder, decoder.status.message.c_str());
    const int sw = (w + denominator - 1) / denominator, sh = (h + denominator - 1) / denominator;
    QCOMPARE((*decoder)->width(), sw);
    QCOMPARE((*decoder)->height(), sh);
    std::vector<std::uint8_t> reduced(static_cast<size_t>(sw) * static_cast<size_t>(sh) * 3);
    QVERIFY((*decoder)->decode(reduced.data(), static_cast<size_t>(sw) * 3).ok);
    double worst = 0.0;
    for (int y = 0; y + 1 < sh; ++y)  // whole blocks only
      for (int x = 0; x + 1 < sw; ++x)
        for (int k = 0; k < 3; ++k) {
          double sum = 0.0;
          for (int dy = 0; dy < denominator; ++dy)
            for (int dx = 0; dx < denominator; ++dx)
              sum += full[(static_cast<size_t>(y * denominator + dy) * static_cast<size_t>(w) +
                           static_cast<size_t>(x * denominator + dx)) * 3 + static_cast<size_t>(k)];
          const double mean = sum / (denominator * denominator);
          worst = std::max(worst, std::abs(mean - reduced[(static_cast<size_t>(y) * static_cast<size_t>(sw) +
                                                           static_cast<size_t>(x)) * 3 + static_cast<size_t>(k)]));
        }
    QVERIFY2(worst <= 4.0, std::to_string(worst).c_str());
  }
};

QTEST_GUILESS_MAIN(TestJpegDecode)
#include "test_jpeg_decode.moc"
