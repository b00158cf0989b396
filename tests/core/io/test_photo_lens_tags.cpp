// SPDX-License-Identifier: Apache-2.0
// photoLensTags: the camera make and model, the lens model and the focal length of a JPEG whose
// EXIF is written by OpenImageIO (a writer other than the exiv2 reader under test; 2.4 puts
// LensModel into IFD0, where the reader looks after the Exif IFD); a file
// without them gives empty tags and focal length 0.
#include "core/io/photo_metadata.h"

#include <OpenImageIO/imageio.h>

#include <QtTest/QtTest>

#include <QTemporaryDir>

#include <vector>

using namespace artcam;

namespace {

bool writeJpeg(const std::string& path, bool tags) {
  std::vector<unsigned char> px(32 * 24 * 3, 128);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  OIIO::ImageSpec spec(32, 24, 3, OIIO::TypeDesc::UINT8);
  if (tags) {
    spec.attribute("Make", "Canon");
    spec.attribute("Model", "Canon PowerShot G11");
    spec.attribute("Exif:LensModel", "6.1-30.5 mm");
    spec.attribute("Exif:FocalLength", 6.1f);
  }
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) &&
         out->close();
}

}  // namespace

class TestPhotoLensTags : public QObject {
  Q_OBJECT

 private slots:
  void readsTheTags() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("tagged.jpg").toStdString();
    QVERIFY(writeJpeg(path, true));
    const auto metadata = readPhotoMetadata(path);
    QVERIFY(metadata);
    const PhotoLensTags tags = photoLensTags(*metadata);
    QCOMPARE(tags.camera_maker, std::string("Canon"));
    QCOMPARE(tags.camera_model, std::string("Canon PowerShot G11"));
    QVERIFY2(tags.lens_model == "6.1-30.5 mm", ("[" + tags.lens_model + "]").c_str());
    QVERIFY(std::abs(tags.focal_mm - 6.1) < 1e-3);
  }

  void absentTagsAreEmpty() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("plain.jpg").toStdString();
    QVERIFY(writeJpeg(path, false));
    const auto metadata = readPhotoMetadata(path);
    if (!metadata) return;  // no metadata at all: nothing to read, nothing to check
    const PhotoLensTags tags = photoLensTags(*metadata);
    QVERIFY(tags.camera_model.empty());
    QVERIFY(tags.lens_model.empty());
    QCOMPARE(tags.focal_mm, 0.0);
  }
};

QTEST_APPLESS_MAIN(TestPhotoLensTags)
#include "test_photo_lens_tags.moc"
