// SPDX-License-Identifier: Apache-2.0
// OpenEXR plates as VFX work brings them, through artcam warp: colour in other primaries (an
// ACEScg plate, its chromaticities attribute AP1/D60) and named OpenColorIO colour spaces.
//
// The truths are outside the code under test: oiiotool's --colorconvert through an OCIO config
// written here, whose ACEScg is OCIO's own built-in AP1 → linear Rec.709 transform (Bradford)
// and whose sRGB is the IEC 61966-2-1 curve as an OCIO exponent-with-linear transform. Without
// oiiotool the comparisons against it fail, saying so.
#include "tests/app/cli_run.h"

#include "core/io/artcam_file.h"
#include "core/model/camera.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <OpenImageIO/imageio.h>

#include <Eigen/Dense>

#include <QFile>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 40, kH = 24;
// ACEScg: the AP1 primaries and the ACES white (SMPTE ST 2065-1, Academy S-2014-004).
const float kAp1[8] = {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f};

const char* kOcioConfig = R"(ocio_profile_version: 2
roles:
  default: lin_rec709
  scene_linear: lin_rec709
file_rules:
  - !<Rule> {name: Default, colorspace: default}
colorspaces:
  - !<ColorSpace>
    name: lin_rec709
  - !<ColorSpace>
    name: ACEScg
    to_scene_reference: !<BuiltinTransform> {style: "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD"}
  - !<ColorSpace>
    name: sRGB
    from_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}
)";

// Colour of texel (x, y): saturated and grey values over 0..1.2, so the primaries matter.
float colourValue(int c, int x, int y) {
  const float t = static_cast<float>(x) / (kW - 1), u = static_cast<float>(y) / (kH - 1);
  const float values[3] = {t * 1.2f, u * (1.0f - 0.5f * t), 0.05f + 0.9f * (1.0f - t) * u};
  return values[c];
}

bool writeExr(const QString& path, const float* chromaticities) {
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::FLOAT);
  if (chromaticities)
    spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities);
  std::vector<float> pixels;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) pixels.push_back(colourValue(c, x, y));
  auto out = OIIO::ImageOutput::create(path.toStdString());
  return out && out->open(path.toStdString(), spec) &&
         out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
}

bool writeIdentityCamera(const QString& path) {
  using namespace artcam;
  const FrameSize frame{kW, kH};
  std::vector<Eigen::Matrix3d> q;
  for (const Eigen::MatrixXd& m : liftHomography(Eigen::Matrix3d::Identity())) q.emplace_back(m);
  return writeArtcam(path.toStdString(), Artcam(Camera::rtcam(q, frame, frame))).ok;
}

struct Pixels {
  OIIO::ImageSpec spec;
  std::vector<float> values;  // as float (integers scaled to 0..1)
};
Pixels readPixels(const QString& path) {
  Pixels p;
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return p;
  p.spec = in->spec();
  p.values.resize(static_cast<size_t>(p.spec.image_pixels()) *
                  static_cast<size_t>(p.spec.nchannels));
  if (!in->read_image(0, 0, 0, p.spec.nchannels, OIIO::TypeDesc::FLOAT, p.values.data()))
    p.values.clear();
  return p;
}

// The largest difference of the first three channels of every pixel; -1 when a file is missing
// or their sizes differ.
double maxDifference(const Pixels& a, const Pixels& b) {
  if (a.values.empty() || b.values.empty() || a.spec.width != b.spec.width ||
      a.spec.height != b.spec.height)
    return -1;
  double worst = 0;
  const size_t pixels = static_cast<size_t>(a.spec.image_pixels());
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::fabs(double(a.values[p * a.spec.nchannels + c]) -
                                        b.values[p * b.spec.nchannels + c]));
  return worst;
}

std::vector<float> chromaticitiesOf(const OIIO::ImageSpec& spec) {
  const OIIO::ParamValue* p = spec.find_attribute("chromaticities");
  if (!p || p->type() != OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8)) return {};
  const auto* v = static_cast<const float*>(p->data());
  return std::vector<float>(v, v + 8);
}

}  // namespace

class TestCliExrPlates : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  QString oiiotool_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // oiiotool through the test's OCIO config; false (after a QFAIL-worthy message) on failure.
  bool oiiotool(const QStringList& args, QString& error) {
    QProcess p;
    p.start(oiiotool_, QStringList{"--colorconfig", path("config.ocio")} + args);
    p.waitForFinished(60000);
    error = QString::fromUtf8(p.readAllStandardError());
    return p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeExr(path("acescg.exr"), kAp1));
    QVERIFY(writeIdentityCamera(path("id.artcam")));
    QFile config(path("config.ocio"));
    QVERIFY(config.open(QIODevice::WriteOnly));
    config.write(kOcioConfig);
    config.close();
    oiiotool_ = QStandardPaths::findExecutable("oiiotool");
  }

  // An ACEScg plate to an 8-bit sRGB PNG: the colour converted from AP1 into sRGB's primaries,
  // within 1/255 of oiiotool --colorconvert ACEScg sRGB.
  void acescgPlateToSrgbPngMatchesOiiotool() {
    if (oiiotool_.isEmpty()) QFAIL("oiiotool is not installed: no outside truth to compare with (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    const Run r = artcamCli({"warp", path("acescg.exr"), path("id.artcam"), "-o", path("out.png"),
                             "--bit-depth", "8", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QString error;
    QVERIFY2(oiiotool({path("acescg.exr"), "--colorconvert", "ACEScg", "sRGB", "-d", "uint8", "-o",
                       path("truth.png")},
                      error),
             qPrintable(error));
    const double worst = maxDifference(readPixels(path("out.png")), readPixels(path("truth.png")));
    qInfo("ACEScg EXR -> sRGB PNG vs oiiotool --colorconvert: max %.3f/255", worst * 255);
    QVERIFY2(worst >= 0 && worst <= 1.0 / 255 + 1e-6,
             qPrintable(QString("max difference %1/255").arg(worst * 255)));
  }

  // To an EXR the plate stays ACEScg by default: labelled AP1 again, values kept (through the
  // float path's conversion there and back: --bit-depth half re-encodes).
  void acescgPlateToExrKeepsItsPrimaries() {
    const Run r = artcamCli({"warp", path("acescg.exr"), path("id.artcam"), "-o", path("kept.exr"),
                             "--bit-depth", "half", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Pixels out = readPixels(path("kept.exr"));
    const std::vector<float> label = chromaticitiesOf(out.spec);
    QCOMPARE(label, std::vector<float>(kAp1, kAp1 + 8));
    const double worst = maxDifference(out, readPixels(path("acescg.exr")));
    QVERIFY2(worst >= 0 && worst <= 1.2 * 1e-3,  // half's step at 1.2 is 2^-10
             qPrintable(QString("max difference %1").arg(worst)));
  }

  // --colourspace srgb: an EXR in the working space, labelled Rec.709/D65, its values those of
  // oiiotool --colorconvert ACEScg lin_rec709.
  void acescgPlateToWorkingSpaceExrMatchesOiiotool() {
    if (oiiotool_.isEmpty()) QFAIL("oiiotool is not installed: no outside truth to compare with (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    const Run r =
        artcamCli({"warp", path("acescg.exr"), path("id.artcam"), "-o", path("rec709.exr"),
                   "--bit-depth", "float", "--colourspace", "srgb", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QString error;
    QVERIFY2(oiiotool({path("acescg.exr"), "--colorconvert", "ACEScg", "lin_rec709", "-o",
                       path("truth.exr")},
                      error),
             qPrintable(error));
    const Pixels out = readPixels(path("rec709.exr"));
    const std::vector<float> rec709 = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    QCOMPARE(chromaticitiesOf(out.spec), rec709);
    const double worst = maxDifference(out, readPixels(path("truth.exr")));
    QVERIFY2(worst >= 0 && worst <= 1e-4, qPrintable(QString("max difference %1").arg(worst)));
  }

  // --colourspace-in names the plate's space where the file says nothing (no chromaticities):
  // through $OCIO's config, the same pixels as oiiotool's conversion.
  void namedInputColourSpaceMatchesOiiotool() {
    if (oiiotool_.isEmpty()) QFAIL("oiiotool is not installed: no outside truth to compare with (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QVERIFY(writeExr(path("unlabelled.exr"), nullptr));
    qputenv("OCIO", path("config.ocio").toUtf8());
    const Run r =
        artcamCli({"warp", path("unlabelled.exr"), path("id.artcam"), "-o", path("named.png"),
                   "--bit-depth", "8", "--colourspace-in", "ACEScg", "-q"});
    qunsetenv("OCIO");
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QString error;
    QVERIFY2(oiiotool({path("unlabelled.exr"), "--colorconvert", "ACEScg", "sRGB", "-d", "uint8",
                       "-o", path("named-truth.png")},
                      error),
             qPrintable(error));
    const double worst =
        maxDifference(readPixels(path("named.png")), readPixels(path("named-truth.png")));
    QVERIFY2(worst >= 0 && worst <= 1.0 / 255 + 1e-6,
             qPrintable(QString("max difference %1/255").arg(worst * 255)));
  }

  // --colourspace-out encodes the output into the named space: a Rec.709 EXR into ACEScg, as
  // oiiotool converts it. ACEScg is a matrix from the working space, so the EXR names its
  // primaries: read back, it gives the sRGB oiiotool makes of the input. sRGB (a curve) names
  // none.
  void namedOutputColourSpaceMatchesOiiotool() {
    if (oiiotool_.isEmpty()) QFAIL("oiiotool is not installed: no outside truth to compare with (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QVERIFY(writeExr(path("unlabelled.exr"), nullptr));
    qputenv("OCIO", path("config.ocio").toUtf8());
    const Run r =
        artcamCli({"warp", path("unlabelled.exr"), path("id.artcam"), "-o", path("to-acescg.exr"),
                   "--bit-depth", "float", "--colourspace-out", "ACEScg", "-q"});
    qunsetenv("OCIO");
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QString error;
    QVERIFY2(oiiotool({path("unlabelled.exr"), "--colorconvert", "lin_rec709", "ACEScg", "-o",
                       path("to-acescg-truth.exr")},
                      error),
             qPrintable(error));
    const Pixels out = readPixels(path("to-acescg.exr"));
    const double worst = maxDifference(out, readPixels(path("to-acescg-truth.exr")));
    QVERIFY2(worst >= 0 && worst <= 1e-5, qPrintable(QString("max difference %1").arg(worst)));
    QCOMPARE(chromaticitiesOf(out.spec).size(), size_t{8});
    const Run back = artcamCli({"warp", path("to-acescg.exr"), path("id.artcam"), "-o",
                                path("back.png"), "--bit-depth", "8", "-q"});
    QVERIFY2(back.exit_code == 0, qPrintable(back.err));
    QVERIFY2(oiiotool({path("unlabelled.exr"), "--colorconvert", "lin_rec709", "sRGB", "-d",
                       "uint8", "-o", path("back-truth.png")},
                      error),
             qPrintable(error));
    const double round_trip =
        maxDifference(readPixels(path("back.png")), readPixels(path("back-truth.png")));
    QVERIFY2(round_trip >= 0 && round_trip <= 1.0 / 255 + 1e-6,
             qPrintable(QString("read back: max difference %1/255").arg(round_trip * 255)));
    qputenv("OCIO", path("config.ocio").toUtf8());
    const Run curve = artcamCli({"warp", path("unlabelled.exr"), path("id.artcam"), "-o",
                                 path("to-srgb.exr"), "--colourspace-out", "sRGB", "-q"});
    qunsetenv("OCIO");
    QVERIFY2(curve.exit_code == 0, qPrintable(curve.err));
    QVERIFY(chromaticitiesOf(readPixels(path("to-srgb.exr")).spec).empty());
  }

  // An unknown name is a usage error in one line naming the option and some valid names, before
  // anything is read or written.
  void unknownColourSpaceIsRefusedInOneLine_data() {
    QTest::addColumn<QString>("option");
    QTest::newRow("in") << "--colourspace-in";
    QTest::newRow("out") << "--colourspace-out";
  }
  void unknownColourSpaceIsRefusedInOneLine() {
    QFETCH(QString, option);
    qputenv("OCIO", path("config.ocio").toUtf8());
    const Run r = artcamCli({"warp", path("acescg.exr"), path("id.artcam"), "-o",
                             path("unknown.png"), option, "ACEScc", "-q"});
    qunsetenv("OCIO");
    QCOMPARE(r.exit_code, 2);
    const QString first = r.err.split('\n').front();
    QVERIFY2(first.contains(option) && first.contains("\"ACEScc\"") && first.contains("ACEScg") &&
                 first.contains("lin_rec709"),
             qPrintable(r.err));
    QVERIFY(!QFile::exists(path("unknown.png")));
  }

  // Chromaticities that make no RGB space are refused in one line naming the file.
  void degenerateChromaticitiesAreRefused() {
    const float flat[8] = {0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3127f, 0.3290f};
    QVERIFY(writeExr(path("flat.exr"), flat));
    const Run r =
        artcamCli({"warp", path("flat.exr"), path("id.artcam"), "-o", path("flat.png"), "-q"});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains(path("flat.exr")) && r.err.contains("chromaticities") &&
                 r.err.trimmed().count('\n') == 0,
             qPrintable(r.err));
    QVERIFY(!QFile::exists(path("flat.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliExrPlates)
#include "test_cli_exr_plates.moc"
