// SPDX-License-Identifier: Apache-2.0
// readFirstLook: a JPEG's first look is exactly libjpeg's DCT-scaled decode of the file (the
// samples the whole read decodes through the sRGB table, fewer of them), upright like the
// whole read, with the whole photo's size; files whose whole read converts colour, and other
// formats, have none.
#include "core/io/first_look.h"
#include "core/io/image_io.h"
#include "core/io/jpeg_decode.h"
#include "core/io/orientation.h"
#include "tests/support/icc_files.h"
#include "tests/support/photo_files.h"

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace artcam;
using namespace artcam::test;

namespace {

// Edges and noise, so a decode that differs anywhere shows it.
OIIO::ImageBuf texture(int width, int height) {
  OIIO::ImageBuf image(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  std::uint32_t seed = 777;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float px[3];
      for (int c = 0; c < 3; ++c) {
        seed = seed * 1664525u + 1013904223u;
        const float noise = static_cast<float>(seed >> 24) / 255.0f;
        px[c] = ((x / 8 + y / 8) % 2 ? 0.6f : 0.3f) + 0.3f * noise;
      }
      image.setpixel(x, y, px, 3);
    }
  return image;
}

// libjpeg's 1/n decode of `path`, as stored.
std::vector<std::uint8_t> scaledDecode(const std::string& path, int n, int* width, int* height) {
  auto decoder = JpegDecoder::open(path, n);
  if (!decoder) return {};
  JpegDecoder& d = **decoder.value;
  *width = d.width();
  *height = d.height();
  const size_t row = static_cast<size_t>(d.width()) * 3;
  std::vector<std::uint8_t> bytes(row * static_cast<size_t>(d.height()));
  if (!d.decode(bytes.data(), row)) return {};
  return bytes;
}

// R, G, B of an opaque RGBA first look; empty when any alpha byte is not 255.
std::vector<std::uint8_t> rgbOf(const StoredImage& image) {
  const auto* p = static_cast<const std::uint8_t*>(image.bytes.data());
  std::vector<std::uint8_t> rgb;
  for (size_t k = 0; k < static_cast<size_t>(image.width) * image.height; ++k, p += 4) {
    if (p[3] != 255) return {};
    rgb.insert(rgb.end(), p, p + 3);
  }
  return rgb;
}

std::vector<std::uint8_t> bytesOf(const StoredImage& image) {
  const auto* first = static_cast<const std::uint8_t*>(image.bytes.data());
  return {first, first + static_cast<size_t>(image.width) * image.height * image.channels};
}

}  // namespace

class TestFirstLook : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  void initTestCase() { QVERIFY(dir_.isValid()); }

  // 4000×400 shrinks to 1920×192 in the box: 1/2 (2000×200) covers 7/8 of it (1680×168),
  // 1/4 (1000×100) does not.
  void reductionCoversTheBox() {
    QCOMPARE(firstLookReduction(4000, 400, 1920, 1080), 2);
    QCOMPARE(firstLookReduction(6000, 4000, 1920, 1080), 4);   // 1500×1000 ≥ 7/8 of 1620×1080
    QCOMPARE(firstLookReduction(5000, 3000, 1920, 1080), 2);   // 1250×750 < 7/8 of 1800×1080
    QCOMPARE(firstLookReduction(16000, 9000, 1920, 1080), 8);  // 2000×1125 ≥ 1920×1080
    QCOMPARE(firstLookReduction(2000, 1200, 1920, 1080), 1);   // 1000×600 < 7/8 of 1800×1080
    // Stored sideways (either way up may be the upright one): covers both, as the same photo
    // stored upright does.
    QCOMPARE(firstLookReduction(4000, 6000, 1920, 1080), 4);
    QCOMPARE(firstLookReduction(3000, 5000, 1920, 1080), 2);
  }

  void jpegFirstLookIsLibjpegsScaledDecode() {
    const std::string file = path("wide.jpg");
    QVERIFY(writeOriented(file, texture(4000, 400), 1, 90));
    const auto look = readFirstLook(file, 1920, 1080);
    QVERIFY2(look, look.status.message.c_str());
    QVERIFY(look->has_value());
    const FirstLook& l = **look;
    QCOMPARE(l.reduced_by, 2);
    QCOMPARE(l.image.width, 2000);
    QCOMPARE(l.image.height, 200);
    QCOMPARE(l.image.channels, 4);  // opaque RGBA (first_look.h)
    QCOMPARE(l.image.alpha_channel, 3);
    QCOMPARE(l.full_width, 4000);
    QCOMPARE(l.full_height, 400);
    int w = 0, h = 0;
    const std::vector<std::uint8_t> truth = scaledDecode(file, 2, &w, &h);
    QCOMPARE(w, 2000);
    QVERIFY(!truth.empty());
    QVERIFY(rgbOf(l.image) == truth);
    // What the whole read says about the file, the first look says too.
    const auto whole = readImage(file);
    QVERIFY2(whole, whole.status.message.c_str());
    QCOMPARE(l.image.info.format_name, whole->info.format_name);
    QCOMPARE(l.image.info.colour_space, whole->info.colour_space);
    QCOMPARE(l.image.info.jpeg_quality, whole->info.jpeg_quality);
    QCOMPARE(l.image.info.stored_orientation, whole->info.stored_orientation);
    QVERIFY(whole->info.srgb && !whole->info.icc);
  }

  // Stored a quarter turn (EXIF 6): turned upright like the whole read; the full size upright.
  void orientationIsHonoured() {
    const OIIO::ImageBuf stored = storedFor(texture(4000, 400), 6);  // 400×4000 as stored
    const std::string turned = path("six.jpg");
    const std::string plain = path("one.jpg");
    QVERIFY(writeOriented(turned, stored, 6, 90));
    QVERIFY(writeOriented(plain, stored, 1, 90));
    const auto look = readFirstLook(turned, 1920, 1080);
    const auto as_stored = readFirstLook(plain, 1920, 1080);
    QVERIFY2(look && *look, look.status.message.c_str());
    QVERIFY2(as_stored && *as_stored, as_stored.status.message.c_str());
    QCOMPARE((*look)->image.info.stored_orientation, 6);
    QCOMPARE((*look)->image.width, 2000);
    QCOMPARE((*look)->image.height, 200);
    QCOMPARE((*look)->full_width, 4000);
    QCOMPARE((*look)->full_height, 400);
    const StoredImage& s = (*as_stored)->image;
    QCOMPARE(s.width, 200);
    std::vector<std::uint8_t> upright(bytesOf(s).size());
    reorientPixels(s.bytes.data(), s.width, s.height, 4, 6, upright.data());
    QVERIFY(bytesOf((*look)->image) == upright);
    const auto whole = readImage(turned);
    QVERIFY2(whole, whole.status.message.c_str());
    QCOMPARE(whole->image.width, 4000);
    QCOMPARE(whole->image.height, 400);
  }

  // Not a JPEG, too small, or a profile the whole read converts through: no first look.
  void otherFilesHaveNone() {
    const std::string png = path("wide.png");
    QVERIFY(writeOriented(png, texture(4000, 400), 1));
    const auto from_png = readFirstLook(png, 1920, 1080);
    QVERIFY2(from_png, from_png.status.message.c_str());
    QVERIFY(!from_png->has_value());

    const std::string small = path("small.jpg");
    QVERIFY(writeOriented(small, texture(2000, 1200), 1, 90));
    const auto from_small = readFirstLook(small, 1920, 1080);
    QVERIFY2(from_small, from_small.status.message.c_str());
    QVERIFY(!from_small->has_value());

    const std::string wide = path("wide-gamut.jpg");
    OIIO::ImageBuf image = texture(4000, 400);
    const std::vector<unsigned char> icc = adobeRgbProfile();  // a wide gamut: converted
    image.specmod().attribute(
        "ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, static_cast<int>(icc.size())),
        icc.data());
    QVERIFY(writeOriented(wide, image, 1, 90));
    const auto whole = readImage(wide);
    QVERIFY2(whole, whole.status.message.c_str());
    QVERIFY(whole->info.icc);  // the whole read converts: the test file is what it says
    const auto from_wide = readFirstLook(wide, 1920, 1080);
    QVERIFY2(from_wide, from_wide.status.message.c_str());
    QVERIFY(!from_wide->has_value());
  }
};

QTEST_GUILESS_MAIN(TestFirstLook)
#include "test_first_look.moc"
