// SPDX-License-Identifier: Apache-2.0
// ICC-tagged images: an Adobe RGB (1998) 16-bit PNG, made here with lcms2 and OpenImageIO, read
// into the working space (linear Rec.709/D65) against the closed form computed from the two
// spaces' primaries and white; written to EXR (chromaticities, no profile), back to 16-bit PNG
// (the same profile, values round-trip) and to sRGB (an sRGB profile). Untagged and
// sRGB-tagged files read exactly as the sRGB curve says; damaged or foreign profiles are
// refused in one line.
#include "core/colour/icc_profile.h"
#include "core/io/image_io.h"
#include "tests/support/icc_files.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <OpenImageIO/imageio.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>

using namespace artcam;
using namespace artcam::test;

namespace {

double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
double linearToSrgb(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// XYZ from linear RGB for primaries (x, y) and a white (x, y), white at Y = 1: the columns are
// the primaries' XYZ scaled so that RGB (1, 1, 1) is the white.
Eigen::Matrix3d xyzFromRgb(const double primaries[3][2], const double white[2]) {
  Eigen::Matrix3d m;
  for (int c = 0; c < 3; ++c) {
    const double x = primaries[c][0], y = primaries[c][1];
    m.col(c) << x / y, 1.0, (1.0 - x - y) / y;
  }
  const Eigen::Vector3d w(white[0] / white[1], 1.0, (1.0 - white[0] - white[1]) / white[1]);
  const Eigen::Vector3d scale = m.inverse() * w;
  return m * scale.asDiagonal();
}

// Linear sRGB from Adobe RGB encoded values, independent of lcms2.
Eigen::Vector3d linearSrgbFromAdobe(const Eigen::Vector3d& encoded) {
  const Eigen::Matrix3d srgb_from_adobe =
      xyzFromRgb(kSrgbPrimaries, kD65).inverse() * xyzFromRgb(kAdobePrimaries, kD65);
  const Eigen::Vector3d linear =
      encoded.unaryExpr([](double v) { return std::pow(v, kAdobeGamma); });
  return srgb_from_adobe * linear;
}

template <class T>
std::vector<T> readRaw(const std::string& path, OIIO::TypeDesc type, OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  spec = in->spec();
  std::vector<T> data(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, type, data.data());
  return data;
}

// Adobe RGB test colours: black, white, the three primaries, and mixed ones.
const std::vector<std::uint16_t> kAdobePixels = {
    0, 0, 0,     65535, 65535, 65535, 0,     65535, 0,     65535, 0,    0,
    0, 0, 65535, 32768, 16384, 49152, 13107, 39321, 26214, 58982, 6554, 19661};

}  // namespace

class TestIcc : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::vector<unsigned char> adobe_icc_ = adobeRgbProfile();  // the bytes adobe.png carries
  std::string path(const char* name) { return dir_.filePath(name).toStdString(); }

  LoadedImage readAdobe() {
    auto loaded = readImage(path("adobe.png"));
    if (!loaded) qWarning("%s", loaded.status.message.c_str());
    return loaded ? std::move(*loaded.value) : LoadedImage{};
  }

 private slots:
  void initTestCase() { QVERIFY(write16(path("adobe.png"), 4, 2, 3, kAdobePixels, adobe_icc_)); }

  void adobeRgbReadsIntoTheWorkingSpace() {
    const LoadedImage loaded = readAdobe();
    QCOMPARE(loaded.image.width, 4);
    QVERIFY(loaded.info.icc);
    QCOMPARE(QString::fromStdString(loaded.info.colour_space), QString("ICC: Adobe RGB (1998)"));
    QVERIFY(!loaded.info.srgb);
    for (size_t p = 0; p < 8; ++p) {
      Eigen::Vector3d encoded;
      for (int c = 0; c < 3; ++c)
        encoded[c] = kAdobePixels[p * 3 + static_cast<size_t>(c)] / 65535.0;
      const Eigen::Vector3d expected = linearSrgbFromAdobe(encoded);
      for (int c = 0; c < 3; ++c) {
        const double got = loaded.image.data[p * 3 + static_cast<size_t>(c)];
        if (std::abs(got - expected[c]) > 1e-3)
          QFAIL(qPrintable(QString("pixel %1 channel %2: %3, closed form %4")
                               .arg(p)
                               .arg(c)
                               .arg(got)
                               .arg(expected[c])));
      }
    }
    // Adobe RGB's pure green lies outside sRGB: negative red and blue survive in float.
    QVERIFY(loaded.image.data[6] < -0.3f);
    QVERIFY(loaded.image.data[8] < -0.02f);
  }

  void exrCarriesTheWorkingChromaticities() {
    const LoadedImage loaded = readAdobe();
    const std::string out = path("adobe.exr");
    QVERIFY(writeImage(out, loaded.image, &loaded.info).ok);
    OIIO::ImageSpec spec;
    const auto values = readRaw<float>(out, OIIO::TypeDesc::FLOAT, spec);
    QVERIFY(profileOf(spec).empty());
    const OIIO::ParamValue* chroma = spec.find_attribute("chromaticities");
    QVERIFY(chroma);
    QCOMPARE(static_cast<int>(chroma->type().numelements() * chroma->type().aggregate), 8);
    const float* xy = static_cast<const float*>(chroma->data());
    const float rec709_d65[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
    for (int k = 0; k < 8; ++k) QCOMPARE(xy[k], rec709_d65[k]);
    QCOMPARE(values.size(), loaded.image.data.size());
    for (size_t k = 0; k < values.size(); ++k)  // half precision, negative values kept
      QVERIFY(std::abs(values[k] - loaded.image.data[k]) <=
              1e-3 * std::max(1.0f, std::abs(loaded.image.data[k])));
  }

  void sameFormatKeepsTheProfileAndValues() {
    const LoadedImage loaded = readAdobe();
    const std::string out = path("again.png");
    QVERIFY(writeImage(out, loaded.image, &loaded.info).ok);
    OIIO::ImageSpec spec;
    const auto values = readRaw<std::uint16_t>(out, OIIO::TypeDesc::UINT16, spec);
    QVERIFY(profileOf(spec) == adobe_icc_);
    QCOMPARE(values.size(), kAdobePixels.size());
    // To the quantisation step, or, where a channel is near 0, to 1e-6 in linear light: the
    // float working values carry ~1e-8 of rounding, which the infinite slope of the pure power
    // curve at 0 magnifies to some 16-bit codes (pure green's red and blue).
    auto linear = [](std::uint16_t v) { return std::pow(v / 65535.0, kAdobeGamma); };
    for (size_t k = 0; k < values.size(); ++k)
      QVERIFY2(
          std::abs(int(values[k]) - int(kAdobePixels[k])) <= 1 ||
              std::abs(linear(values[k]) - linear(kAdobePixels[k])) <= 1e-6,
          qPrintable(QString("sample %1: %2, was %3").arg(k).arg(values[k]).arg(kAdobePixels[k])));
  }

  void srgbOutputIsEncodedAndLabelledSrgb() {
    const LoadedImage loaded = readAdobe();
    const std::string out = path("srgb.png");
    WriteImageOptions options;
    options.colour_space = WriteImageOptions::ColourSpace::Srgb;
    QVERIFY(writeImage(out, loaded.image, &loaded.info, options).ok);
    OIIO::ImageSpec spec;
    const auto values = readRaw<std::uint16_t>(out, OIIO::TypeDesc::UINT16, spec);
    const auto profile = IccProfile::fromBytes(profileOf(spec), 3, out);
    QVERIFY(profile.ok());
    QVERIFY(profile->equivalentToSrgb());
    for (size_t k = 0; k < values.size(); ++k) {
      const double expected = linearToSrgb(loaded.image.data[k]) * 65535.0;  // clipped to gamut
      QVERIFY(std::abs(values[k] - expected) <= 1.0);
    }
  }

  void untaggedAndSrgbTaggedReadAsBefore() {
    const std::vector<std::uint16_t> pixels = {0, 1000, 20000, 40000, 65535, 33333};
    const std::string untagged = path("untagged.png"), tagged = path("tagged.png");
    QVERIFY(write16(untagged, 2, 1, 3, pixels, {}));
    QVERIFY(write16(tagged, 2, 1, 3, pixels, IccProfile::srgbBytes()));
    for (const std::string& file : {untagged, tagged}) {
      const auto loaded = readImage(file);
      QVERIFY(loaded.ok());
      QVERIFY(!loaded->info.icc);
      QCOMPARE(QString::fromStdString(loaded->info.colour_space), QString("sRGB"));
      for (size_t k = 0; k < pixels.size(); ++k)
        QCOMPARE(loaded->image.data[k], static_cast<float>(srgbToLinear(pixels[k] / 65535.0)));
    }
  }

  void greyProfileDecodesItsCurve() {
    const std::vector<std::uint16_t> pixels = {0, 16384, 32768, 65535};
    const std::string in = path("grey.png");
    QVERIFY(write16(in, 4, 1, 1, pixels, greyGammaProfile(2.2)));
    const auto loaded = readImage(in);
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QVERIFY(loaded->info.icc);
    for (size_t k = 0; k < pixels.size(); ++k)
      QVERIFY(std::abs(loaded->image.data[k] - std::pow(pixels[k] / 65535.0, 2.2)) <= 1e-3);
  }

  void damagedOrForeignProfilesAreRefused() {
    std::vector<unsigned char> damaged = adobeRgbProfile();
    damaged.resize(200);  // header and a cut tag table
    const std::string cut = path("cut-icc.tif");
    QVERIFY(write16(cut, 2, 1, 3, {1, 2, 3, 4, 5, 6}, damaged));
    const auto refused = readImage(cut);
    QVERIFY(!refused.ok());
    QVERIFY(refused.status.message.find('\n') == std::string::npos);
    QVERIFY(refused.status.message.rfind(cut + ": cannot read: its embedded ICC profile", 0) == 0);

    const std::string rgb_on_grey = path("rgb-on-grey.tif");
    QVERIFY(write16(rgb_on_grey, 2, 1, 1, {1, 2}, adobeRgbProfile()));
    const auto foreign = readImage(rgb_on_grey);
    QVERIFY(!foreign.ok());
    QVERIFY2(foreign.status.message.find("describes RGB colour, the pixels are grey") !=
                 std::string::npos,
             foreign.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestIcc)
#include "test_icc.moc"
