// SPDX-License-Identifier: Apache-2.0
// Photos as they come, through `artcam warp` and `artcam batch` run as processes: a portrait
// JPEG stored sideways (EXIF orientation 6) is warped upright and written with orientation 1,
// its XMP packet (rights, rating) reaches the output on both the stored-type and the float
// path, the JPEG quality is the input's unless --quality says otherwise, --bit-depth sets the
// output's sample type, and bad values are refused in one line. Fixtures and read-backs use
// OpenImageIO and exiv2 directly.
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/model/camera.h"
#include "tests/app/cli_run.h"
#include "tests/support/photo_files.h"

#include <QtTest/QtTest>

#include <QFile>
#include <QTemporaryDir>

#include <cmath>

using namespace artcam;
using namespace artcam::test;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 32, kH = 48;  // the upright portrait; stored 48x32

std::string pixelFormat(const QString& file) {
  auto in = OIIO::ImageInput::open(file.toStdString());
  return in ? std::string(in->spec().format.c_str()) : std::string("(unreadable)");
}

}  // namespace

class TestCliPhotoMetadata : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }
  OIIO::ImageBuf upright_ = quadrantPhoto(kW, kH);

  // The output shows the upright quadrants (an identity camera of the upright frame). JPEG at
  // quality 61 moves a flat colour by up to about 0.04; quadrants differ by 0.7 or more.
  bool showsUprightPhoto(const QString& file) const {
    auto in = OIIO::ImageInput::open(file.toStdString());
    if (!in || in->spec().width != kW || in->spec().height != kH) return false;
    std::vector<float> pixels(static_cast<size_t>(kW) * kH * 3);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data())) return false;
    for (int y : {kH / 4, 3 * kH / 4})
      for (int x : {kW / 4, 3 * kW / 4}) {
        float expected[3];
        upright_.getpixel(x, y, expected, 3);
        for (int c = 0; c < 3; ++c)
          if (std::abs(pixels[(static_cast<size_t>(y) * kW + x) * 3 + c] - expected[c]) > 0.06f)
            return false;
      }
    return true;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeOriented(path("portrait.jpg").toStdString(), storedFor(upright_, 6), 6, 88));
    Exiv2::XmpData xmp;
    xmp["Xmp.dc.rights"] = "lang=x-default (c) The Photographer";
    xmp["Xmp.xmp.Rating"] = 5;
    xmp["Xmp.tiff.Orientation"] = "6";
    addXmp(path("portrait.jpg").toStdString(), xmp);
    const Camera identity = Camera::identity({Block{BlockKind::Position, 3}}, {kW, kH}, {kW, kH});
    QVERIFY(writeArtcam(path("identity.artcam").toStdString(), Artcam(identity)).ok);
    QVERIFY(writeOriented(path("reference61.jpg").toStdString(), upright_, 1, 61));
  }

  // JPEG to JPEG (the stored-type path) and JPEG to 16-bit TIFF (the float path): upright,
  // orientation 1 in EXIF and XMP, the XMP fields as the input had them.
  void warpedUprightWithTheInputsXmp() {
    for (const QStringList& extra : {QStringList{}, QStringList{"--bit-depth", "16"}}) {
      const QString out = path(extra.isEmpty() ? "upright.jpg" : "upright16.tif");
      const Run r = artcamCli(QStringList{"warp", path("portrait.jpg"), path("identity.artcam"),
                                          "-o", out, "--filter", "nearest", "-q"} +
                              extra);
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      QVERIFY2(!r.err.contains("warning"), qPrintable(r.err));  // the upright size fits
      QVERIFY2(showsUprightPhoto(out), qPrintable(out));
      const Exiv2Read in = readWithExiv2(path("portrait.jpg").toStdString());
      const Exiv2Read written = readWithExiv2(out.toStdString());
      QCOMPARE(exifText(written, "Exif.Image.Orientation"), std::string("1"));
      QCOMPARE(xmpText(written, "Xmp.tiff.Orientation"), std::string("1"));
      QCOMPARE(xmpText(written, "Xmp.dc.rights"), xmpText(in, "Xmp.dc.rights"));
      QCOMPARE(xmpText(written, "Xmp.xmp.Rating"), xmpText(in, "Xmp.xmp.Rating"));
      QCOMPARE(xmpText(written, "Xmp.xmp.Rating"), std::string("5"));
    }
    QCOMPARE(pixelFormat(path("upright16.tif")), std::string("uint16"));
  }

  // Without --quality a JPEG keeps its quantisation tables; with it, they are libjpeg's own
  // for that quality (a JPEG OpenImageIO wrote at 61).
  void qualityIsTheInputsUnlessGiven() {
    const Run kept = artcamCli(
        {"warp", path("portrait.jpg"), path("identity.artcam"), "-o", path("kept.jpg"), "-q"});
    QVERIFY2(kept.exit_code == 0, qPrintable(kept.err));
    QCOMPARE(jpegQuantisationTables(path("kept.jpg").toStdString()),
             jpegQuantisationTables(path("portrait.jpg").toStdString()));
    const Run set = artcamCli({"warp", path("portrait.jpg"), path("identity.artcam"), "-o",
                               path("q61.jpg"), "--quality", "61", "-q"});
    QVERIFY2(set.exit_code == 0, qPrintable(set.err));
    const std::string reference = jpegQuantisationTables(path("reference61.jpg").toStdString());
    QCOMPARE(jpegQuantisationTables(path("q61.jpg").toStdString()), reference);
    QVERIFY(reference != jpegQuantisationTables(path("portrait.jpg").toStdString()));

    const Run batch = artcamCli({"batch", path("identity.artcam"), path("portrait.jpg"), "-o",
                                 path("batch"), "--quality", "61", "--bit-depth", "8", "-q"});
    QVERIFY2(batch.exit_code == 0, qPrintable(batch.err));
    QCOMPARE(jpegQuantisationTables(path("batch/portrait.jpg").toStdString()), reference);
    QVERIFY(showsUprightPhoto(path("batch/portrait.jpg")));
    QCOMPARE(xmpText(readWithExiv2(path("batch/portrait.jpg").toStdString()), "Xmp.xmp.Rating"),
             std::string("5"));
  }

  void bitDepthSetsTheSampleType() {
    const Run half = artcamCli({"warp", path("portrait.jpg"), path("identity.artcam"), "-o",
                                path("half.exr"), "--bit-depth", "half", "-q"});
    QVERIFY2(half.exit_code == 0, qPrintable(half.err));
    QCOMPARE(pixelFormat(path("half.exr")), std::string("half"));
    const Run batch = artcamCli({"batch", path("identity.artcam"), path("portrait.jpg"), "-o",
                                 path("batch16"), "--format", "png", "--bit-depth", "16", "-q"});
    QVERIFY2(batch.exit_code == 0, qPrintable(batch.err));
    QCOMPARE(pixelFormat(path("batch16/portrait.png")), std::string("uint16"));
    QVERIFY(showsUprightPhoto(path("batch16/portrait.png")));
  }

  void badValuesAreRefusedInOneLine() {
    const struct {
      const char* option;
      const char* value;
      const char* message;
    } cases[] = {{"--quality", "0", "--quality expects a whole number from 1 to 100, got \"0\""},
                 {"--quality", "101", "--quality expects a whole number from 1 to 100"},
                 {"--quality", "9x", "--quality expects a whole number from 1 to 100"},
                 {"--bit-depth", "12", "--bit-depth expects 8, 16, half or float, not \"12\""}};
    for (const auto& c : cases) {
      const Run warp = artcamCli({"warp", path("portrait.jpg"), path("identity.artcam"), "-o",
                                  path("refused.jpg"), c.option, c.value});
      const Run batch = artcamCli({"batch", path("identity.artcam"), path("portrait.jpg"), "-o",
                                   path("refused"), c.option, c.value});
      for (const Run& r : {warp, batch}) {
        QCOMPARE(r.exit_code, 2);
        const QStringList lines = r.err.trimmed().split('\n');
        QVERIFY2(lines.first().contains(c.message), qPrintable(r.err));
        QVERIFY2(lines.size() == 2 && lines.last().startsWith("see 'artcam"), qPrintable(r.err));
      }
      QVERIFY(!QFile::exists(path("refused.jpg")));
      QVERIFY(!QFile::exists(path("refused/portrait.jpg")));
    }
  }
};

QTEST_GUILESS_MAIN(TestCliPhotoMetadata)
#include "test_cli_photo_metadata.moc"
