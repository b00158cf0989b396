// SPDX-License-Identifier: Apache-2.0
// Vignetting from the command line (issue 49): `artcam lens camera --aperture` (and the EXIF's
// f-number with --from), `artcam fit --flat-field`, and a flat-field camera composed before a
// lens camera. The pictures are made here with OpenImageIO; the flat field follows the cos⁴ law
// of natural vignetting about an axis off the frame's centre, so the truth is that law, not the
// model the fit uses. (lensfun's own modifier is the truth of tests/core/lens/
// test_lens_vignetting.cpp.)
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QtTest/QtTest>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>
#include <vector>

using artcam::test::artcamCli;

namespace {

const char* const kPrime = "Canon EF 50mm f/1.8 MkII";
constexpr int kW = 450, kH = 300;
const double kAxisX = 245.0, kAxisY = 137.0;

double cos4(double x, double y) {
  const double f = 0.9 * 0.5 * std::hypot(double(kW), double(kH));
  const double c = f / std::hypot(f, std::hypot(x - kAxisX, y - kAxisY));
  return c * c * c * c;
}

bool writeFloat(const QString& path, const std::vector<float>& px, int channels = 3) {
  auto out = OIIO::ImageOutput::create(path.toStdString());
  if (!out) return false;
  const OIIO::ImageSpec spec(kW, kH, channels, OIIO::TypeDesc::FLOAT);
  return out->open(path.toStdString(), spec) &&
         out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close();
}

std::vector<float> cosFourthField(bool black_corner = false) {
  std::vector<float> px(size_t(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        px[(size_t(y) * kW + x) * 3 + c] =
            black_corner && x < 30 && y < 30 ? 0.0f : float(0.6 * cos4(x + 0.5, y + 0.5));
  return px;
}

std::vector<float> pixels(const QString& path, int* channels = nullptr) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data())) return {};
  if (channels) *channels = spec.nchannels;
  return px;
}

QJsonObject json(const QString& text) { return QJsonDocument::fromJson(text.toUtf8()).object(); }

}  // namespace

class TestCliVignetting : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(name); }

 private slots:
  void lensCameraAperture() {
    const QStringList base = {"lens",        "camera", "--lens",        kPrime,   "--focal",
                              "50",          "--crop", "1.6",           "--size", "450x300",
                              "--overwrite", "-o",     path("v.artcam")};
    auto r = artcamCli(base + QStringList{"--aperture", "2", "--json"});
    QCOMPARE(r.exit_code, 0);
    QJsonObject j = json(r.out);
    QVERIFY2(j["vignetting"].toBool(), qPrintable(r.out));
    QCOMPARE(j["aperture"].toDouble(), 2.0);
    QVERIFY(j["vignetting_max_percent"].toDouble() > 0.0);
    QVERIFY(j["vignetting_max_percent"].toDouble() < 0.5);
    r = artcamCli(base + QStringList{"--aperture", "2"});
    QVERIFY2(r.out.contains("vignetting at f/2: gain max"), qPrintable(r.out));
    const auto info = artcamCli({"info", path("v.artcam")});
    QVERIFY2(info.out.contains("shading(2)"), qPrintable(info.out));

    // Without an aperture, or with --no-vignetting: none, and the first says why.
    r = artcamCli(base + QStringList{"--json"});
    j = json(r.out);
    QVERIFY(!j["vignetting"].toBool());
    QVERIFY(QJsonDocument(j["notes"].toArray()).toJson().contains("give the aperture"));
    r = artcamCli(base + QStringList{"--aperture", "2", "--no-vignetting", "--json"});
    QVERIFY(!json(r.out)["vignetting"].toBool());
    r = artcamCli(base + QStringList{"--aperture", "-2"});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("--aperture"), qPrintable(r.err));
  }

  // --from takes the f-number from the EXIF (Exif:FNumber, written by OpenImageIO here), and
  // makes the camera --lens … --aperture makes.
  void apertureFromExif() {
    std::vector<unsigned char> px(size_t(kW) * kH * 3, 128);
    const QString photo = path("shot.jpg");
    auto out = OIIO::ImageOutput::create(photo.toStdString());
    OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Make", "Canon");
    spec.attribute("Model", "Canon EOS 550D");
    spec.attribute("Exif:LensModel", kPrime);
    spec.attribute("Exif:FocalLength", 50.0f);
    spec.attribute("FNumber", 2.8f);
    QVERIFY(out && out->open(photo.toStdString(), spec) &&
            out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
    auto r = artcamCli({"lens", "camera", "--from", photo, "-o", path("exif.artcam"), "--json"});
    QCOMPARE(r.exit_code, 0);
    const QJsonObject j = json(r.out);
    QCOMPARE(j["aperture"].toDouble(), 2.8);
    QVERIFY2(j["vignetting"].toBool(), qPrintable(r.out));
    r = artcamCli({"lens", "camera", "--lens", kPrime, "--focal", "50", "--crop",
                   QString::number(j["crop"].toDouble(), 'g', 17), "--size", "450x300",
                   "--aperture", "2.8", "-o", path("named.artcam")});
    QCOMPARE(r.exit_code, 0);
    QFile a(path("exif.artcam")), b(path("named.artcam"));
    QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly));
    QCOMPARE(a.readAll(), b.readAll());
  }

  // A cos⁴ flat field about an axis off the centre: the fitted camera finds the axis and makes
  // the field flat within 1 %; a field with a black corner is refused in one line naming it.
  void flatField() {
    QVERIFY(writeFloat(path("flat.exr"), cosFourthField()));
    auto r =
        artcamCli({"fit", "--flat-field", path("flat.exr"), "-o", path("flat.artcam"), "--json"});
    QCOMPARE(r.exit_code, 0);
    const QJsonObject j = json(r.out);
    const QJsonArray centre = j["centre_px"].toArray();
    QVERIFY2(std::hypot(centre[0].toDouble() - kAxisX, centre[1].toDouble() - kAxisY) < 3.0,
             qPrintable(r.out));
    QVERIFY2(j["darkest"].toDouble() < 0.65, qPrintable(r.out));
    QVERIFY(j["max_percent"].toDouble() < 1.0);
    r = artcamCli({"warp", path("flat.exr"), path("flat.artcam"), "-o", path("flattened.exr")});
    QCOMPARE(r.exit_code, 0);
    int channels = 0;
    const std::vector<float> px = pixels(path("flattened.exr"), &channels);
    QVERIFY(!px.empty());
    double lo = 1e9, hi = 0;
    for (size_t i = 0; i < px.size(); i += size_t(channels)) {
      lo = std::min(lo, double(px[i + 1]));
      hi = std::max(hi, double(px[i + 1]));
    }
    QVERIFY2(hi / lo - 1.0 < 0.01, qPrintable(QString("%1 … %2").arg(lo).arg(hi)));
    QVERIFY2(std::abs(hi - 0.6) < 0.01, qPrintable(QString::number(hi)));

    QVERIFY(writeFloat(path("black.exr"), cosFourthField(true)));
    r = artcamCli({"fit", "--flat-field", path("black.exr"), "-o", path("black.artcam")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("black.exr") && r.err.contains("(0, 0)"), qPrintable(r.err));
    QVERIFY(r.err.trimmed().count('\n') < 3);
    QVERIFY(!QFile::exists(path("black.artcam")));
    r = artcamCli(
        {"fit", "--flat-field", path("flat.exr"), "--lines", "x.csv", "-o", path("x.artcam")});
    QCOMPARE(r.exit_code, 2);
    r = artcamCli({"fit", "--cells", "8", "m.csv", "-o", path("x.artcam"), "--size", "4x4"});
    QCOMPARE(r.exit_code, 2);
  }

  // A flat-field camera composes before a layered (TCA) lens camera: the one camera gives the
  // pixels of the two warps one after the other (the first keeps every pixel in place).
  void composesBeforeTheLens() {
    QVERIFY(writeFloat(path("flat.exr"), cosFourthField()));
    QCOMPARE(
        artcamCli({"fit", "--flat-field", path("flat.exr"), "-o", path("f.artcam"), "--overwrite"})
            .exit_code,
        0);
    QCOMPARE(artcamCli({"lens", "camera", "--lens", "Lumix G Vario 45-200mm f/4.0-5.6 Mega OIS",
                        "--focal", "45", "--size", "450x300", "-o", path("tca.artcam")})
                 .exit_code,
             0);
    auto r =
        artcamCli({"compose", path("f.artcam"), path("tca.artcam"), "-o", path("both.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QCOMPARE(
        artcamCli({"warp", path("flat.exr"), path("both.artcam"), "-o", path("one.exr")}).exit_code,
        0);
    QCOMPARE(
        artcamCli({"warp", path("flat.exr"), path("f.artcam"), "-o", path("step.exr")}).exit_code,
        0);
    QCOMPARE(
        artcamCli({"warp", path("step.exr"), path("tca.artcam"), "-o", path("two.exr")}).exit_code,
        0);
    const std::vector<float> one = pixels(path("one.exr")), two = pixels(path("two.exr"));
    QCOMPARE(one.size(), two.size());
    double worst = 0.0;
    for (size_t i = 0; i < one.size(); ++i)
      worst = std::max(worst, double(std::abs(one[i] - two[i])));
    QVERIFY2(worst < 2e-3, qPrintable(QString::number(worst)));
  }
};

QTEST_MAIN(TestCliVignetting)
#include "test_cli_vignetting.moc"
