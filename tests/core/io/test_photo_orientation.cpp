// SPDX-License-Identifier: Apache-2.0
// EXIF orientation: a raster stored turned or mirrored (as cameras store portraits) reads
// upright through both readers, float (readImage) and stored-type (readStoredImage), and is
// written upright with orientation 1. The stored rasters are made with OpenImageIO's
// ImageBufAlgo, checked against its own reorient, never with the engine's turn.
#include "core/io/image_io.h"
#include "core/io/orientation.h"
#include "core/io/stored_image.h"
#include "tests/support/photo_files.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

#include <cmath>
#include <cstring>

using namespace artcam;
using namespace artcam::test;

namespace {

std::vector<std::uint8_t> bytesOf(const OIIO::ImageBuf& image) {
  std::vector<std::uint8_t> bytes(image.spec().image_pixels() *
                                  static_cast<size_t>(image.nchannels()));
  image.get_pixels(image.roi(), OIIO::TypeDesc::UINT8, bytes.data());
  return bytes;
}

double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

}  // namespace

class TestPhotoOrientation : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  // Lossless TIFF: every orientation, every pixel exact.
  void allEightOrientationsReadUpright() {
    QVERIFY(dir_.isValid());
    const int kW = 7, kH = 4;
    OIIO::ImageBuf upright(OIIO::ImageSpec(kW, kH, 3, OIIO::TypeDesc::UINT8));
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float px[3] = {x / 10.0f, y / 10.0f, 0.5f};  // every pixel its own colour
        upright.setpixel(x, y, px, 3);
      }
    const std::vector<std::uint8_t> truth = bytesOf(upright);
    QVERIFY(writeOriented(path("upright.tif"), upright, 1));
    const auto reference = readImage(path("upright.tif"));
    QVERIFY(reference);

    for (int o = 1; o <= 8; ++o) {
      OIIO::ImageBuf stored = storedFor(upright, o);
      stored.specmod().attribute("Orientation", o);
      // The fixture is what OpenImageIO itself turns upright, except 5 and 7, which
      // OpenImageIO 2.4's reorient swaps (it transverses 5 and transposes 7; the reason the
      // engine turns rasters itself, orientation.h). Those two are checked against TIFF 6.0's
      // words: 5, stored row 0 is the left column and stored column 0 the top row; 7, stored
      // row 0 is the right column and stored column 0 the bottom row.
      if (o == 5 || o == 7) {
        float s00[3], s10[3], u0[3], u1[3];
        stored.getpixel(0, 0, s00, 3);
        stored.getpixel(1, 0, s10, 3);
        upright.getpixel(o == 5 ? 0 : kW - 1, o == 5 ? 0 : kH - 1, u0, 3);
        upright.getpixel(o == 5 ? 0 : kW - 1, o == 5 ? 1 : kH - 2, u1, 3);
        QVERIFY(std::memcmp(s00, u0, sizeof s00) == 0 && std::memcmp(s10, u1, sizeof s10) == 0);
      } else {
        QCOMPARE(bytesOf(OIIO::ImageBufAlgo::reorient(stored)), truth);
      }
      const std::string file = path(("o" + std::to_string(o) + ".tif").c_str());
      QVERIFY(writeOriented(file, stored, o));

      const auto loaded = readImage(file);
      QVERIFY2(loaded, loaded.status.message.c_str());
      QCOMPARE(loaded->image.width, kW);
      QCOMPARE(loaded->image.height, kH);
      QVERIFY2(loaded->image.data == reference->image.data, qPrintable(QString::number(o)));
      QCOMPARE(loaded->info.stored_orientation, o);

      const auto kept = readStoredImage(file);
      QVERIFY2(kept, kept.status.message.c_str());
      QCOMPARE(kept->width, kW);
      QCOMPARE(kept->height, kH);
      QVERIFY2(std::memcmp(kept->bytes.data(), truth.data(), truth.size()) == 0,
               qPrintable(QString::number(o)));
      QCOMPARE(kept->info.stored_orientation, o);
    }
  }

  // A portrait JPEG stored as a landscape raster tagged 6 reads upright, and what is written
  // from it is upright, says orientation 1 and reads back the same way round.
  void jpegTaggedSixReadsUprightAndIsWrittenWithOne() {
    const int kW = 32, kH = 48;  // upright portrait
    const OIIO::ImageBuf upright = quadrantPhoto(kW, kH);
    QVERIFY(writeOriented(path("six.jpg"), storedFor(upright, 6), 6));
    QCOMPARE(readWithExiv2(path("six.jpg"))
                 .exif.findKey(Exiv2::ExifKey("Exif.Image.Orientation"))
                 ->toLong(),
             6L);

    auto quadrantsMatch = [&](const ImageF& image) {
      for (int y : {kH / 4, 3 * kH / 4})
        for (int x : {kW / 4, 3 * kW / 4}) {
          float expected[3];
          upright.getpixel(x, y, expected, 3);
          for (int c = 0; c < 3; ++c) {
            const double want = srgbToLinear(std::round(expected[c] * 255.0) / 255.0);
            if (std::abs(image.pixel(x, y)[c] - want) > 0.02) return false;
          }
        }
      return true;
    };
    const auto loaded = readImage(path("six.jpg"));
    QVERIFY2(loaded, loaded.status.message.c_str());
    QCOMPARE(loaded->image.width, kW);
    QCOMPARE(loaded->image.height, kH);
    QVERIFY(quadrantsMatch(loaded->image));

    QVERIFY(writeImage(path("out.jpg"), loaded->image, &loaded->info).ok);
    const Exiv2Read written = readWithExiv2(path("out.jpg"));
    QCOMPARE(exifText(written, "Exif.Image.Orientation"), std::string("1"));
    auto in = OIIO::ImageInput::open(path("out.jpg"));
    QVERIFY(in);
    QCOMPARE(in->spec().width, kW);
    QCOMPARE(in->spec().height, kH);
    const auto again = readImage(path("out.jpg"));
    QVERIFY(again);
    QCOMPARE(again->info.stored_orientation, 1);
    QVERIFY(quadrantsMatch(again->image));

    // The stored-type path turns it the same way and writes orientation 1 too.
    const auto kept = readStoredImage(path("six.jpg"));
    QVERIFY2(kept, kept.status.message.c_str());
    QCOMPARE(kept->width, kW);
    QCOMPARE(kept->height, kH);
    QVERIFY(writeStoredImage(path("kept.jpg"), kept->view(), &kept->info).ok);
    QCOMPARE(exifText(readWithExiv2(path("kept.jpg")), "Exif.Image.Orientation"), std::string("1"));
    const auto kept_again = readImage(path("kept.jpg"));
    QVERIFY(kept_again);
    QCOMPARE(kept_again->image.width, kW);
    QVERIFY(quadrantsMatch(kept_again->image));
  }

  // EXIF first: an XMP tiff:Orientation (OpenImageIO 2.4 lets it override EXIF, and misses it
  // alone) counts only where the file has no EXIF orientation.
  void exifOrientationWinsOverXmp() {
    const OIIO::ImageBuf landscape = quadrantPhoto(48, 32);
    Exiv2::XmpData xmp;
    xmp["Xmp.tiff.Orientation"] = "6";
    QVERIFY(writeOriented(path("exif1.jpg"), landscape, 1));
    addXmp(path("exif1.jpg"), xmp);
    const auto exif_one = readImage(path("exif1.jpg"));
    QVERIFY(exif_one);
    QCOMPARE(exif_one->image.width, 48);
    QCOMPARE(exif_one->info.stored_orientation, 1);

    QVERIFY(writeOriented(path("xmp-only.jpg"), landscape, 1));
    {
      auto image = Exiv2::ImageFactory::open(path("xmp-only.jpg"));
      image->readMetadata();
      Exiv2::ExifData exif = image->exifData();
      exif.erase(exif.findKey(Exiv2::ExifKey("Exif.Image.Orientation")));
      image->setExifData(exif);
      image->setXmpData(xmp);
      image->writeMetadata();
    }
    QCOMPARE(exifText(readWithExiv2(path("xmp-only.jpg")), "Exif.Image.Orientation"),
             std::string("(none)"));
    const auto xmp_six = readImage(path("xmp-only.jpg"));
    QVERIFY(xmp_six);
    QCOMPARE(xmp_six->image.width, 32);
    QCOMPARE(xmp_six->info.stored_orientation, 6);
  }

  // Out-of-range tags are taken as 1 (what viewers do), not refused.
  void invalidOrientationIsTakenAsOne() {
    QCOMPARE(validOrientation(0), 1);
    QCOMPARE(validOrientation(9), 1);
    QCOMPARE(validOrientation(6), 6);
  }
};

QTEST_GUILESS_MAIN(TestPhotoOrientation)
#include "test_photo_orientation.moc"
