// SPDX-License-Identifier: Apache-2.0
// A photo's EXIF, IPTC and XMP reach the files written from it (writeImage, writeStoredImage):
// every XMP field, a history event for the save added, with the stale fields (pixel size,
// thumbnail, colour space when the transfer changes) updated; and a JPEG keeps its quality.
// Fixtures are written with OpenImageIO and exiv2 directly, and read back with them.
#include "core/io/image_io.h"
#include "core/io/jpeg_quality.h"
#include "core/io/stored_image.h"
#include "tests/support/photo_files.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

using namespace artcam;
using namespace artcam::test;

class TestPhotoMetadata : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }
  std::string source_packet_;

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeOriented(path("photo.jpg"), quadrantPhoto(40, 30), 1, 90));
    QVERIFY(writeOriented(path("thumb.jpg"), quadrantPhoto(8, 6), 1, 50));
    // What a camera and a photo manager add: EXIF with a thumbnail, IPTC, an XMP packet with
    // fields OpenImageIO does not know (a custom namespace as darktable and Lightroom use).
    auto image = Exiv2::ImageFactory::open(path("photo.jpg"));
    image->readMetadata();
    Exiv2::ExifData exif = image->exifData();
    exif["Exif.Image.Make"] = "TestCam";
    exif["Exif.Photo.PixelXDimension"] = std::uint32_t{40};
    exif["Exif.Photo.PixelYDimension"] = std::uint32_t{30};
    exif["Exif.Photo.ColorSpace"] = std::uint16_t{1};
    Exiv2::ExifThumb(exif).setJpegThumbnail(path("thumb.jpg"));
    image->setExifData(exif);
    Exiv2::IptcData iptc;
    iptc["Iptc.Application2.Caption"] = "A caption";
    image->setIptcData(iptc);
    Exiv2::XmpProperties::registerNs("http://example.org/edits/1.0/", "edits");
    Exiv2::XmpData xmp;
    xmp["Xmp.dc.rights"] = "lang=x-default (c) The Tester";
    xmp["Xmp.xmp.Rating"] = 3;
    xmp["Xmp.xmpRights.UsageTerms"] = "lang=x-default Ask first";
    xmp["Xmp.edits.history"] = "exposure +0.3; crop";
    image->setXmpData(xmp);
    image->writeMetadata();
    source_packet_ = readWithExiv2(path("photo.jpg")).xmp_packet;
    QVERIFY(!source_packet_.empty());
    QVERIFY(Exiv2::ExifThumbC(readWithExiv2(path("photo.jpg")).exif).copy().size_ != 0);
  }

  // JPEG, TIFF and PNG outputs of another size: EXIF, IPTC and XMP as the photo had them,
  // the pixel size updated, the stale thumbnail gone.
  void carriedToEveryFormatExiv2Writes() {
    const auto loaded = readImage(path("photo.jpg"));
    QVERIFY2(loaded, loaded.status.message.c_str());
    const ImageF smaller(20, 15, 3);  // a warp's output need not keep the size
    for (const char* name : {"out.jpg", "out.tif", "out.png"}) {
      QVERIFY2(writeImage(path(name), smaller, &loaded->info).ok, name);
      const Exiv2Read out = readWithExiv2(path(name));
      QCOMPARE(xmpText(out, "Xmp.dc.rights"), std::string("lang=\"x-default\" (c) The Tester"));
      QCOMPARE(xmpText(out, "Xmp.xmp.Rating"), std::string("3"));
      QCOMPARE(xmpText(out, "Xmp.xmpRights.UsageTerms"),
               std::string("lang=\"x-default\" Ask first"));
      QCOMPARE(xmpText(out, "Xmp.edits.history"), std::string("exposure +0.3; crop"));
      // Re-serialised with this save's history event (photo_metadata.h): artcam, "saved".
      QVERIFY2(xmpText(out, "Xmp.xmpMM.History[1]/stEvt:softwareAgent").rfind("artcam ", 0) == 0,
               name);
      QCOMPARE(xmpText(out, "Xmp.xmpMM.History[1]/stEvt:action"), std::string("saved"));
      QVERIFY2(exifText(out, "Exif.Image.Software").rfind("artcam ", 0) == 0, name);
      QCOMPARE(exifText(out, "Exif.Image.Make"), std::string("TestCam"));
      QCOMPARE(exifText(out, "Exif.Photo.PixelXDimension"), std::string("20"));
      QCOMPARE(exifText(out, "Exif.Photo.PixelYDimension"), std::string("15"));
      QVERIFY2(Exiv2::ExifThumbC(out.exif).copy().size_ == 0, name);
      const auto caption = out.iptc.findKey(Exiv2::IptcKey("Iptc.Application2.Caption"));
      QVERIFY2(caption != out.iptc.end(), name);
      QCOMPARE(caption->toString(), std::string("A caption"));
    }
    // The TIFF is still a TIFF of the written size: its own raster tags won.
    QCOMPARE(exifText(readWithExiv2(path("out.tif")), "Exif.Image.ImageWidth"), std::string("20"));
  }

  // The colour-space tag stays where the transfer does and goes where it changed.
  void colourSpaceTagFollowsTheTransfer() {
    const auto loaded = readImage(path("photo.jpg"));
    QVERIFY(loaded);
    const ImageF image(20, 15, 3);
    QVERIFY(writeImage(path("same.tif"), image, &loaded->info).ok);
    QCOMPARE(exifText(readWithExiv2(path("same.tif")), "Exif.Photo.ColorSpace"), std::string("1"));
    WriteImageOptions linear;
    linear.pixel_type = "float";  // float TIFF is written linear
    QVERIFY(writeImage(path("linear.tif"), image, &loaded->info, linear).ok);
    const Exiv2Read out = readWithExiv2(path("linear.tif"));
    QCOMPARE(exifText(out, "Exif.Photo.ColorSpace"), std::string("(none)"));
    QCOMPARE(xmpText(out, "Xmp.xmp.Rating"), std::string("3"));
  }

  // OpenEXR is no format exiv2 writes: the save still succeeds.
  void formatsExiv2CannotWriteStillSave() {
    const auto loaded = readImage(path("photo.jpg"));
    QVERIFY(loaded);
    const Status s = writeImage(path("out.exr"), ImageF(20, 15, 3), &loaded->info);
    QVERIFY2(s.ok, s.message.c_str());
  }

  // The stored-type writer carries the same.
  void storedWriterCarriesItToo() {
    const auto kept = readStoredImage(path("photo.jpg"));
    QVERIFY(kept);
    QVERIFY(writeStoredImage(path("kept.jpg"), kept->view(), &kept->info).ok);
    const Exiv2Read out = readWithExiv2(path("kept.jpg"));
    QCOMPARE(xmpText(out, "Xmp.edits.history"), std::string("exposure +0.3; crop"));
    QVERIFY(xmpText(out, "Xmp.xmpMM.History[1]/stEvt:softwareAgent").rfind("artcam ", 0) == 0);
    QCOMPARE(exifText(out, "Exif.Photo.PixelXDimension"), std::string("40"));
    QVERIFY(Exiv2::ExifThumbC(out.exif).copy().size_ == 0);
  }

  // Quality: the estimate gives back what libjpeg (through OpenImageIO) was asked for, and a
  // JPEG written from a JPEG keeps its quantisation tables unless told otherwise.
  void jpegQualityIsKept() {
    for (int q : {10, 50, 77, 100}) {
      const std::string file = path(("q" + std::to_string(q) + ".jpg").c_str());
      QVERIFY(writeOriented(file, quadrantPhoto(16, 16), 1, q));
      QCOMPARE(estimateJpegQuality(file), q);
    }
    QCOMPARE(estimateJpegQuality(path("out.png")), 0);
    const auto loaded = readImage(path("q77.jpg"));
    QVERIFY(loaded);
    QCOMPARE(loaded->info.jpeg_quality, 77);
    QVERIFY(writeImage(path("kept77.jpg"), loaded->image, &loaded->info).ok);
    QCOMPARE(jpegQuantisationTables(path("kept77.jpg")), jpegQuantisationTables(path("q77.jpg")));
    WriteImageOptions options;
    options.jpeg_quality = 50;
    QVERIFY(writeImage(path("now50.jpg"), loaded->image, &loaded->info, options).ok);
    QCOMPARE(jpegQuantisationTables(path("now50.jpg")), jpegQuantisationTables(path("q50.jpg")));
    // Not from a JPEG: 95, as before.
    QVERIFY(writeOriented(path("q95.jpg"), quadrantPhoto(16, 16), 1, 95));
    const auto png = readImage(path("out.png"));
    QVERIFY(png);
    QVERIFY(writeImage(path("from-png.jpg"), png->image, &png->info).ok);
    QCOMPARE(jpegQuantisationTables(path("from-png.jpg")), jpegQuantisationTables(path("q95.jpg")));
  }
};

QTEST_GUILESS_MAIN(TestPhotoMetadata)
#include "test_photo_metadata.moc"
