// SPDX-License-Identifier: Apache-2.0
// Stored-value fidelity (image_io.h, "Channels" and "ICC profiles"): both readers keep colour and
// alpha as the image and every other channel as an extra one, with or without alpha (a
// renderer's R,G,B,Z; a five-sample TIFF), and such images are written back with their extra
// channels; and the stored-value readers take the float path's decision on an embedded profile:
// damaged and foreign profiles refused with the same line, a converting one kept as info.icc, a
// CMYK JPEG's dropped and carried into no output. Files are made here with OpenImageIO.
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "tests/support/exr_files.h"
#include "tests/support/icc_files.h"

#include <OpenImageIO/imageio.h>

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

using namespace artcam;
using namespace artcam::test;

namespace {

constexpr int kW = 8, kH = 6;

// An 8-bit file of `names.size()` channels, alpha at `alpha` (-1: none), every sample `value`
// but channel c's, which is value + c, tagged with `icc` when it is not empty.
bool write8(const std::string& path, const std::vector<std::string>& names, int alpha,
            const std::vector<unsigned char>& icc = {}, int value = 40) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) return false;
  const int n = static_cast<int>(names.size());
  OIIO::ImageSpec spec(kW, kH, n, OIIO::TypeDesc::UINT8);
  spec.channelnames = names;
  spec.alpha_channel = alpha;
  if (!icc.empty()) setProfile(spec, icc);
  std::vector<std::uint8_t> data(static_cast<size_t>(kW * kH * n));
  for (size_t k = 0; k < data.size(); ++k)
    data[k] = static_cast<std::uint8_t>(value + static_cast<int>(k % static_cast<size_t>(n)));
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, data.data()) &&
         out->close();
}

OIIO::ImageSpec specOf(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  return in ? in->spec() : OIIO::ImageSpec();
}

}  // namespace

class TestStoredFidelity : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  // R,G,B,Z without alpha is RGB and a Z on both paths, not four colour channels.
  void extraChannelsWithoutAlphaAreExtraChannels() {
    const std::string file = path("rgbz.exr");
    QVERIFY(writeFloatExr(file, kW, kH, {"R", "G", "B", "Z"}, -1, 0, 0,
                          [](int c, int, int) { return c == 3 ? 7.5f : 0.25f * (c + 1); }));
    auto stored = readStoredImage(file);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    QCOMPARE(stored->channels, 3);
    QCOMPARE(stored->alpha_channel, -1);
    QCOMPARE(stored->info.dropped_channels, std::vector<std::string>({"Z"}));
    auto loaded = readImage(file);
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QCOMPARE(loaded->image.channels, 3);
    QCOMPARE(loaded->info.dropped_channels, std::vector<std::string>({"Z"}));
  }

  // The same rule with alpha: the image ends at alpha (Y,A then a Z; a five-sample TIFF).
  void theImageEndsAtAlpha() {
    const std::string grey = path("yaz.exr");
    QVERIFY(writeFloatExr(grey, kW, kH, {"Y", "A", "Z"}, 1, 0, 0,
                          [](int c, int, int) { return c == 2 ? 3.0f : 0.5f; }));
    auto stored = readStoredImage(grey);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    QCOMPARE(stored->channels, 2);
    QCOMPARE(stored->alpha_channel, 1);
    QCOMPARE(stored->info.dropped_channels, std::vector<std::string>({"Z"}));

    const std::string tiff = path("five.tif");
    QVERIFY(write8(tiff, {"R", "G", "B", "X", "Y"}, -1));
    QCOMPARE(specOf(tiff).alpha_channel, -1);
    auto five = readStoredImage(tiff);
    QVERIFY2(five.ok(), five.status.message.c_str());
    QCOMPARE(five->channels, 3);
    QCOMPARE(five->info.dropped_channels.size(), size_t(2));
  }

  // What a warp makes of R,G,B,Z (an alpha added where pixels have no preimage, Z beside) is
  // written back by both writers, every channel by name.
  void rgbWithAddedAlphaAndZIsWrittenBack() {
    const std::string file = path("rgbz-half.exr");
    {
      auto out = OIIO::ImageOutput::create(file);
      OIIO::ImageSpec spec(kW, kH, 4, OIIO::TypeDesc::HALF);
      spec.channelnames = {"R", "G", "B", "Z"};
      std::vector<float> px(static_cast<size_t>(kW * kH * 4), 0.5f);
      for (size_t k = 3; k < px.size(); k += 4) px[k] = 7.5f;
      QVERIFY(out->open(file, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
              out->close());
    }
    auto stored = readStoredImage(file);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    auto extra = readExtraChannels(file, stored->info);
    QVERIFY2(extra.ok(), extra.status.message.c_str());
    QCOMPARE(extra->names(), std::vector<std::string>({"Z"}));
    QCOMPARE(stored->channels, 3);

    // RGB plus the alpha a render adds (pixel 0 transparent).
    StoredImage rgba = makeStoredImage(kW, kH, 4, 3, PixelType::Float);
    auto* px = static_cast<float*>(static_cast<void*>(rgba.bytes.data()));
    for (int p = 0; p < kW * kH; ++p)
      for (int c = 0; c < 4; ++c) px[p * 4 + c] = p == 0 ? 0.0f : c == 3 ? 1.0f : 0.5f;
    WriteImageOptions options;
    options.extra_channels = &*extra;
    const std::string stored_out = path("stored-out.exr");
    const Status s =
        writeStoredImage(stored_out, std::as_const(rgba).view(), &stored->info, options);
    QVERIFY2(s.ok, s.message.c_str());
    const OIIO::ImageSpec written = specOf(stored_out);
    QCOMPARE(written.nchannels, 5);
    QCOMPARE(written.channelnames, std::vector<std::string>({"R", "G", "B", "A", "Z"}));
    QCOMPARE(written.format, OIIO::TypeDesc(OIIO::TypeDesc::HALF));  // as it came
    std::vector<float> back(static_cast<size_t>(kW * kH * 5));
    auto in = OIIO::ImageInput::open(stored_out);
    QVERIFY(in && in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, back.data()));
    QCOMPARE(back[5 + 4], 7.5f);  // pixel 1's Z
    QCOMPARE(back[5 + 3], 1.0f);  // pixel 1's alpha
    QCOMPARE(back[3], 0.0f);      // pixel 0 transparent

    auto loaded = readImage(file);
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    ImageF image(kW, kH, 4, 3);
    for (size_t k = 0; k < image.data.size(); ++k) image.data[k] = k % 4 == 3 ? 1.0f : 0.5f;
    const std::string float_out = path("float-out.exr");
    const Status f = writeImage(float_out, image, &loaded->info, options);
    QVERIFY2(f.ok, f.message.c_str());
    QCOMPARE(specOf(float_out).channelnames, std::vector<std::string>({"R", "G", "B", "A", "Z"}));
  }

  // Damaged and foreign profiles: the stored-value reader refuses what the float reader
  // refuses, with the same line, for JPEG (the codec's path) and TIFF (OpenImageIO's).
  void storedPathRefusesWhatTheFloatPathRefuses() {
    const std::vector<unsigned char> grey = greyGammaProfile(2.2);
    const std::vector<unsigned char> adobe = adobeRgbProfile();
    const std::vector<unsigned char> truncated(adobe.begin(), adobe.begin() + 200);
    std::vector<unsigned char> garbage = {'a', 'c', 's', 'p'};
    for (int k = 0; k < 300; ++k) garbage.push_back(static_cast<unsigned char>((k * 37) % 256));
    const struct {
      const char* name;
      std::vector<unsigned char> icc;
      const char* cause;
    } cases[] = {{"grey", grey, "describes grey colour, the pixels are RGB"},
                 {"lab", labProfile(), "describes Lab colour, the pixels are RGB"},
                 {"cut", truncated, "is damaged"},
                 {"garbage", garbage, "is damaged"}};
    for (const auto& c : cases)
      for (const char* ext : {".jpg", ".tif"}) {
        const std::string file = path((std::string("icc-") + c.name + ext).c_str());
        QVERIFY(write8(file, {"R", "G", "B"}, -1, c.icc));
        QVERIFY2(specOf(file).find_attribute("ICCProfile") != nullptr, file.c_str());
        auto loaded = readImage(file);
        auto stored = readStoredImage(file);
        QVERIFY2(!loaded.ok() && loaded.status.message.find(c.cause) != std::string::npos,
                 (file + ": " + loaded.status.message).c_str());
        QVERIFY2(!stored.ok(), (file + ": the stored-value reader took it").c_str());
        QCOMPARE(stored.status.message, loaded.status.message);
      }
  }

  // A JPEG whose profile is CMYK (the RGB a reader makes of inks, or a mislabelled RGB): read
  // as sRGB on both paths, the profile dropped, and no output labelled with it.
  void aCmykProfileOnAJpegIsDroppedOnEveryPath() {
    const std::string file = path("cmyk-profile.jpg");
    QVERIFY(write8(file, {"R", "G", "B"}, -1, cmykHeaderProfile()));
    auto stored = readStoredImage(file);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    QVERIFY(!stored->info.icc);
    auto loaded = readImage(file);
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    // Both readers say the profile was not applied (ImageInfo::profile_dropped says why).
    QCOMPARE(stored->info.colour_space, loaded->info.colour_space);
    QVERIFY(stored->info.colour_space.find("not applied") != std::string::npos);
    for (const char* name : {"cmyk-out.png", "cmyk-out.jpg", "cmyk-out.tif"}) {
      const Status s = writeStoredImage(path(name), std::as_const(*stored).view(), &stored->info);
      QVERIFY2(s.ok, s.message.c_str());
      QVERIFY2(profileOf(specOf(path(name))).empty(), name);
    }
    WriteImageOptions sixteen;
    sixteen.pixel_type = "uint16";
    const Status f = writeImage(path("cmyk-float.png"), loaded->image, &loaded->info, sixteen);
    QVERIFY2(f.ok, f.message.c_str());
    QVERIFY(profileOf(specOf(path("cmyk-float.png"))).empty());
  }

  // A profile that describes the pixels is the stored values' label: recorded as info.icc, as
  // the float reader records it, and carried with the values.
  void aConvertingProfileIsKeptWithTheStoredValues() {
    const std::string file = path("adobe.png");
    const std::vector<unsigned char> adobe = adobeRgbProfile();
    QVERIFY(write16(file, 4, 2, 3, std::vector<std::uint16_t>(24, 30000), adobe));
    auto stored = readStoredImage(file);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    QVERIFY(stored->info.icc);
    QCOMPARE(stored->info.colour_space, readImage(file)->info.colour_space);
    const Status s =
        writeStoredImage(path("adobe-out.png"), std::as_const(*stored).view(), &stored->info);
    QVERIFY2(s.ok, s.message.c_str());
    QCOMPARE(profileOf(specOf(path("adobe-out.png"))), adobe);
  }
};

QTEST_GUILESS_MAIN(TestStoredFidelity)
#include "test_stored_fidelity.moc"
