// SPDX-License-Identifier: Apache-2.0
// Stored-value fidelity through artcam warp and batch: a renderer's R,G,B,Z (no alpha) is
// warped with its Z into an EXR even where the camera leaves pixels transparent, and into a PNG
// without it, with one warning, its Z never taken for alpha; a JPEG's CMYK profile labels no
// output (one warning line), and a foreign profile is refused on the stored-value path as on
// the float path. Files are made here with OpenImageIO.
#include "tests/app/cli_run.h"
#include "tests/support/icc_files.h"

#include <OpenImageIO/imageio.h>

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <string>
#include <vector>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 64, kH = 48;

bool writeRgbz(const std::string& path, float z) {
  OIIO::ImageSpec spec(kW, kH, 4, OIIO::TypeDesc::HALF);
  spec.channelnames = {"R", "G", "B", "Z"};
  std::vector<float> px(static_cast<size_t>(kW * kH * 4), 0.5f);
  for (size_t k = 3; k < px.size(); k += 4) px[k] = z;
  auto out = OIIO::ImageOutput::create(path);
  return out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
         out->close();
}

bool writeJpeg(const std::string& path, const std::vector<unsigned char>& icc) {
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
  artcam::test::setProfile(spec, icc);
  std::vector<unsigned char> px(static_cast<size_t>(kW * kH * 3), 120);
  auto out = OIIO::ImageOutput::create(path);
  return out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) &&
         out->close();
}

OIIO::ImageSpec specOf(const QString& path) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  return in ? in->spec() : OIIO::ImageSpec();
}

int lines(const QString& text) { return static_cast<int>(text.trimmed().split('\n').size()); }

}  // namespace

class TestCliFidelity : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QCOMPARE(
        artcamCli({"preset", "barrel", "--size", "64x48", "-o", path("barrel.artcam")}).exit_code,
        0);
    // The identity camera of the frame: every pixel has a preimage, so no alpha is added.
    QFile identity(path("identity.artcam"));
    QVERIFY(identity.open(QIODevice::WriteOnly));
    identity.write(
        R"({"format": "artcam", "version": 1, "blocks": [{"kind": "position", "size": 3}],
      "frames": {"source": [64, 48], "target": [64, 48]},
      "stages": [{"tensors": [[[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]],
                              [[0, 0, 0], [0, 0, 0.5], [0, 0.5, 0]],
                              [[0, 0, 0], [0, 0, 0], [0, 0, 1]]]}]})");
  }

  void rgbzThroughACameraWithHolesKeepsItsZ() {
    QVERIFY(writeRgbz(path("rgbz.exr").toStdString(), 5.0f));
    const Run r =
        artcamCli({"warp", path("rgbz.exr"), path("barrel.artcam"), "-o", path("out.exr")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const OIIO::ImageSpec spec = specOf(path("out.exr"));
    QCOMPARE(spec.channelnames, std::vector<std::string>({"R", "G", "B", "A", "Z"}));
    QCOMPARE(spec.format, OIIO::TypeDesc(OIIO::TypeDesc::HALF));
    std::vector<float> px(static_cast<size_t>(kW * kH * 5));
    auto in = OIIO::ImageInput::open(path("out.exr").toStdString());
    QVERIFY(in && in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, px.data()));
    const size_t centre = (static_cast<size_t>(kH / 2) * kW + kW / 2) * 5;
    QCOMPARE(px[centre + 4], 5.0f);  // depth by the nearest texel: the stored Z
    QCOMPARE(px[centre + 3], 1.0f);
    QCOMPARE(px[3], 0.0f);  // a corner without a preimage
  }

  void rgbzIntoAPngLeavesZOutAndNeverMakesItAlpha() {
    QVERIFY(writeRgbz(path("rgbz-low.exr").toStdString(), 0.25f));
    const Run r =
        artcamCli({"warp", path("rgbz-low.exr"), path("identity.artcam"), "-o", path("out.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("rgbz-low.exr: channels beyond colour and alpha (Z) are not warped"),
             qPrintable(r.err));
    QCOMPARE(lines(r.err), 1);
    QCOMPARE(specOf(path("out.png")).nchannels, 3);  // opaque RGB: a Z of 0.25 is no alpha

    const Run holes =
        artcamCli({"warp", path("rgbz-low.exr"), path("barrel.artcam"), "-o", path("holes.png")});
    QVERIFY2(holes.exit_code == 0, qPrintable(holes.err));
    QCOMPARE(specOf(path("holes.png")).nchannels, 4);
  }

  void aJpegsCmykProfileLabelsNoOutput() {
    QVERIFY(writeJpeg(path("cmyk.jpg").toStdString(), artcam::test::cmykHeaderProfile()));
    for (const char* name : {"cmyk-out.png", "cmyk-out.jpg"}) {
      const Run r =
          artcamCli({"warp", path("cmyk.jpg"), path("identity.artcam"), "-o", path(name)});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      QVERIFY2(r.err.contains("cmyk.jpg: its embedded CMYK ICC profile does not describe") &&
                   r.err.contains("carries no profile"),
               qPrintable(r.err));
      QCOMPARE(lines(r.err), 1);
      QVERIFY2(!specOf(path(name)).find_attribute("ICCProfile"), name);
    }
    const Run b = artcamCli({"batch", path("identity.artcam"), path("cmyk.jpg"), "-o",
                             path("batch"), "--format", "png", "-q"});
    QVERIFY2(b.exit_code == 0, qPrintable(b.err));
    QVERIFY2(b.err.contains("artcam batch: warning: ") && b.err.contains("carries no profile"),
             qPrintable(b.err));
  }

  void aForeignProfileIsRefusedOnTheStoredPathToo() {
    QVERIFY(writeJpeg(path("grey-profile.jpg").toStdString(), artcam::test::greyGammaProfile(2.2)));
    for (const char* name : {"grey-out.jpg", "grey-out.png", "grey-out.exr"}) {
      const Run r =
          artcamCli({"warp", path("grey-profile.jpg"), path("identity.artcam"), "-o", path(name)});
      QCOMPARE(r.exit_code, 1);
      QVERIFY2(r.err.contains("grey-profile.jpg: cannot read: its embedded ICC profile describes "
                              "grey colour, the pixels are RGB"),
               qPrintable(r.err));
      QCOMPARE(lines(r.err), 1);
      QVERIFY(!QFile::exists(path(name)));
    }
  }
};

QTEST_GUILESS_MAIN(TestCliFidelity)
#include "test_cli_fidelity.moc"
