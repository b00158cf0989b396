// SPDX-License-Identifier: Apache-2.0
// What exiftool sees in artcam's outputs: a camera JPEG's EXIF and XMP tags (over 40, tagged
// by exiftool itself) come back from HEIC, AVIF, WebP and JPEG outputs with their values, but
// for the ones that describe the new file (Software names artcam, the photo's own tool kept as
// an xmpMM:History event; pixel sizes; orientation); a 4:4:4 JPEG stays 4:4:4 unless
// --subsampling says otherwise. Fails, saying so, when exiftool is not installed.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <vector>

using artcam::test::artcamCli;

namespace {

QJsonObject exiftool(const QString& exe, const QStringList& args) {
  QProcess p;
  p.start(exe, QStringList{"-j", "-a", "-G1", "-struct"} + args);
  if (!p.waitForFinished(60000) || p.exitCode() != 0) return {};
  const QJsonArray all = QJsonDocument::fromJson(p.readAllStandardOutput()).array();
  return all.isEmpty() ? QJsonObject() : all[0].toObject();
}

// Tags that describe a photo rather than its file: EXIF (IFD0, ExifIFD, GPS) and XMP groups.
bool photoTag(const QString& key) {
  const QString group = key.section(':', 0, 0);
  return group == "IFD0" || group == "ExifIFD" || group == "GPS" || group.startsWith("XMP-");
}

// Tags that must change: the writer, the new file's size and orientation, its history, the
// XMP serialiser's name.
bool describesTheFile(const QString& key) {
  const QString tag = key.section(':', 1);
  return tag == "Software" || tag == "ExifImageWidth" || tag == "ExifImageHeight" ||
         tag == "Orientation" || tag == "History" || tag == "ImageWidth" || tag == "ImageHeight" ||
         tag == "XMPToolkit";  // the library that serialised the packet
}

}  // namespace

class TestCliOutputMetadata : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(name); }
  QString exiftool_;
  QString version_;

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    exiftool_ = QStandardPaths::findExecutable("exiftool");
    const auto v = artcamCli({"--version"});
    QCOMPARE(v.exit_code, 0);
    version_ = v.out.trimmed();  // "artcam 0.1.0"
    // A 4:4:4 JPEG, as a camera set to its finest chroma writes.
    OIIO::ImageSpec spec(96, 64, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("jpeg:subsampling", "4:4:4");
    std::vector<unsigned char> px(96 * 64 * 3);
    for (size_t k = 0; k < px.size(); ++k) px[k] = static_cast<unsigned char>((k * 37) % 251);
    auto out = OIIO::ImageOutput::create(path("photo.jpg").toStdString());
    QVERIFY(out && out->open(path("photo.jpg").toStdString(), spec) &&
            out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
    const auto cam = artcamCli(
        {"preset", "barrel", "--k", "-0.05", "--size", "96x64", "-o", path("lens.artcam")});
    QVERIFY2(cam.exit_code == 0, qPrintable(cam.err));
  }

  void exiftoolSeesThePhotosTagsInEveryOutput() {
    if (exiftool_.isEmpty()) QFAIL("exiftool (Debian's libimage-exiftool-perl) is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    // What a camera and a photo manager write, tagged by exiftool.
    QProcess tag;
    tag.start(exiftool_, {"-overwrite_original",
                          "-Make=TestCam",
                          "-Model=T1",
                          "-Software=TestCam FW 2.1",
                          "-Artist=A. Tester",
                          "-Copyright=(c) A. Tester",
                          "-ImageDescription=A test scene",
                          "-DateTimeOriginal=2024:05:06 07:08:09",
                          "-CreateDate=2024:05:06 07:08:09",
                          "-ModifyDate=2024:05:06 07:08:10",
                          "-ExposureTime=1/250",
                          "-FNumber=5.6",
                          "-ISO=200",
                          "-FocalLength=35",
                          "-FocalLengthIn35mmFormat=52",
                          "-ExposureProgram=Manual",
                          "-MeteringMode=Spot",
                          "-Flash=No Flash",
                          "-WhiteBalance=Manual",
                          "-LensModel=TestLens 35mm F2",
                          "-LensMake=TestOptics",
                          "-BodySerialNumber=12345",
                          "-ExposureCompensation=-0.3",
                          "-MaxApertureValue=2",
                          "-SubjectDistance=3.5",
                          "-UserComment=hello",
                          "-ExifVersion=0232",
                          "-GPSLatitude=48.1",
                          "-GPSLatitudeRef=N",
                          "-GPSLongitude=11.5",
                          "-GPSLongitudeRef=E",
                          "-GPSAltitude=520",
                          "-GPSAltitudeRef=Above Sea Level",
                          "-XMP-dc:Title=Test title",
                          "-XMP-dc:Description=A test scene",
                          "-XMP-dc:Creator=A. Tester",
                          "-XMP-dc:Rights=(c) A. Tester",
                          "-XMP-dc:Subject=test",
                          "-XMP-xmp:Rating=4",
                          "-XMP-xmp:Label=Green",
                          "-XMP-photoshop:City=Munich",
                          "-XMP-photoshop:Country=Germany",
                          "-XMP-photoshop:Headline=Headline",
                          "-XMP-xmpRights:UsageTerms=Ask first",
                          "-XMP-xmpRights:Marked=True",
                          "-XMP-iptcCore:Location=Old town",
                          "-ExifImageWidth=4000",
                          "-ExifImageHeight=3000",  // stale after a warp
                          path("photo.jpg")});
    QVERIFY(tag.waitForFinished(60000) && tag.exitCode() == 0);
    const QJsonObject in = exiftool(exiftool_, {path("photo.jpg")});
    QStringList kept;
    for (auto it = in.begin(); it != in.end(); ++it)
      if (photoTag(it.key()) && !describesTheFile(it.key())) kept << it.key();
    qInfo("%lld photo tags in the fixture (exiftool)", static_cast<long long>(kept.size()));
    QVERIFY2(kept.size() >= 40,
             qPrintable(QString("only %1 tags in the fixture").arg(kept.size())));

    for (const char* name : {"out.heic", "out.avif", "out.webp", "out.jpg"}) {
      const auto run = artcamCli(
          {"warp", path("photo.jpg"), path("lens.artcam"), "-o", path(name), "--overwrite", "-q"});
      QVERIFY2(run.exit_code == 0, qPrintable(run.err));
      const QJsonObject out = exiftool(exiftool_, {path(name)});
      QVERIFY2(!out.isEmpty(), name);
      for (const QString& key : kept)
        QVERIFY2(out.value(key) == in.value(key),
                 qPrintable(QString("%1: %2 is %3, was %4")
                                .arg(name, key,
                                     QString::fromUtf8(QJsonDocument(QJsonArray{out.value(key)})
                                                           .toJson(QJsonDocument::Compact)),
                                     QString::fromUtf8(QJsonDocument(QJsonArray{in.value(key)})
                                                           .toJson(QJsonDocument::Compact)))));
      // The writer is artcam; the camera's firmware is the history's first agent.
      QCOMPARE(out.value("IFD0:Software").toString(), version_);
      const QJsonArray history = out.value("XMP-xmpMM:History").toArray();
      QVERIFY2(history.size() == 2, name);
      QCOMPARE(history[0].toObject().value("SoftwareAgent").toString(), QString("TestCam FW 2.1"));
      QCOMPARE(history[1].toObject().value("SoftwareAgent").toString(), version_);
      QCOMPARE(history[1].toObject().value("Action").toString(), QString("saved"));
      QCOMPARE(out.value("ExifIFD:ExifImageWidth").toInt(), 96);
      QCOMPARE(out.value("ExifIFD:ExifImageHeight").toInt(), 64);
    }
  }

  // The stored-value path (a plain warp) and the float path (a pixel type change) alike.
  void chromaSubsamplingIsKeptUnlessAsked() {
    if (exiftool_.isEmpty()) QFAIL("exiftool (Debian's libimage-exiftool-perl) is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    const auto sub = [&](const char* name) {
      return exiftool(exiftool_, {"-YCbCrSubSampling", "-n", path(name)})
          .value("File:YCbCrSubSampling")
          .toString();
    };
    QCOMPARE(sub("photo.jpg"), QString("1 1"));
    const struct {
      const char* name;
      QStringList extra;
      const char* expected;
    } cases[] = {{"kept.jpg", {}, "1 1"},
                 {"kept-float.jpg", {"--colourspace", "srgb", "--bit-depth", "8"}, "1 1"},
                 {"s420.jpg", {"--subsampling", "420"}, "2 2"},
                 {"s422.jpg", {"--subsampling", "422"}, "2 1"}};
    for (const auto& c : cases) {
      const auto run = artcamCli(QStringList{"warp", path("photo.jpg"), path("lens.artcam"), "-o",
                                             path(c.name), "--overwrite", "-q"} +
                                 c.extra);
      QVERIFY2(run.exit_code == 0, qPrintable(run.err));
      QCOMPARE(sub(c.name), QString(c.expected));
    }
    // A PNG input has no subsampling to keep: libjpeg's 4:2:0.
    QVERIFY(artcamCli({"warp", path("photo.jpg"), path("lens.artcam"), "-o", path("p.png"), "-q"})
                .exit_code == 0);
    QVERIFY(
        artcamCli({"warp", path("p.png"), path("lens.artcam"), "-o", path("from-png.jpg"), "-q"})
            .exit_code == 0);
    QCOMPARE(sub("from-png.jpg"), QString("2 2"));
    const auto bad = artcamCli({"warp", path("photo.jpg"), path("lens.artcam"), "-o", path("x.jpg"),
                                "--subsampling", "411"});
    QCOMPARE(bad.exit_code, 2);
    QVERIFY2(bad.err.contains("--subsampling expects 444, 422 or 420"), qPrintable(bad.err));
  }
};

QTEST_GUILESS_MAIN(TestCliOutputMetadata)
#include "test_cli_output_metadata.moc"
