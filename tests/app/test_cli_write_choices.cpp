// SPDX-License-Identifier: Apache-2.0
// What warp keeps or takes for a format beyond the pixels, read back by clients that are not
// ours: a 10-bit DPX stays 10-bit (OpenImageIO's DPX reader, as `iinfo -v` prints it);
// --quality on a PNG sets zlib's level as ImageMagick reads it (the FLEVEL bits of the zlib
// stream's header, RFC 1950), the pixels the same at every level.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QFile>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <vector>

using artcam::test::artcamCli;

namespace {

constexpr int kW = 64, kH = 48;

// The FLEVEL field (0 fastest … 3 maximum) of the zlib stream in the PNG's first IDAT chunk.
int pngZlibLevel(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return -1;
  const QByteArray bytes = f.readAll();
  const int at = bytes.indexOf("IDAT");
  if (at < 0 || at + 6 > bytes.size()) return -1;
  return (static_cast<unsigned char>(bytes[at + 5]) >> 6) & 3;
}

std::vector<float> pixels(const QString& path, int* bits = nullptr) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return {};
  if (bits) *bits = in->spec().get_int_attribute("oiio:BitsPerSample", 0);
  std::vector<float> px(static_cast<size_t>(in->spec().image_pixels() * in->spec().nchannels));
  return in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, px.data())
             ? px
             : std::vector<float>();
}

}  // namespace

class TestCliWriteChoices : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(name); }

  bool write(const char* name, OIIO::TypeDesc type) {
    OIIO::ImageSpec spec(kW, kH, 3, type);
    std::vector<float> px(static_cast<size_t>(kW * kH * 3));
    for (size_t k = 0; k < px.size(); ++k) px[k] = static_cast<float>((k * 53) % 1021) / 1020.0f;
    auto out = OIIO::ImageOutput::create(path(name).toStdString());
    return out && out->open(path(name).toStdString(), spec) &&
           out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close();
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    const auto cam = artcamCli(
        {"preset", "barrel", "--k", "-0.05", "--size", "64x48", "-o", path("lens.artcam")});
    QVERIFY2(cam.exit_code == 0, qPrintable(cam.err));
  }

  void tenAndTwelveBitDpxKeepTheirBits() {
    for (const auto& [name, type, bits] :
         {std::tuple{"ten.dpx", OIIO::TypeDesc(OIIO::TypeDesc::UINT16), 10},
          std::tuple{"twelve.dpx", OIIO::TypeDesc(OIIO::TypeDesc::UINT16), 12}}) {
      OIIO::ImageSpec spec(kW, kH, 3, type);
      spec.attribute("oiio:BitsPerSample", bits);
      std::vector<unsigned short> px(static_cast<size_t>(kW * kH * 3), 30000);
      auto out = OIIO::ImageOutput::create(path(name).toStdString());
      QVERIFY(out && out->open(path(name).toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::UINT16, px.data()) && out->close());
      int in_bits = 0;
      QVERIFY(!pixels(path(name), &in_bits).empty());
      QCOMPARE(in_bits, bits);
      const QString warped = path(name) + ".out.dpx";
      const auto run = artcamCli({"warp", path(name), path("lens.artcam"), "-o", warped, "-q"});
      QVERIFY2(run.exit_code == 0, qPrintable(run.err));
      int out_bits = 0;
      QVERIFY(!pixels(warped, &out_bits).empty());
      QCOMPARE(out_bits, bits);
      // --bit-depth 16 asks for 16 bits.
      const QString sixteen = path(name) + ".16.dpx";
      QVERIFY(artcamCli({"warp", path(name), path("lens.artcam"), "-o", sixteen, "-q",
                         "--bit-depth", "16"})
                  .exit_code == 0);
      pixels(sixteen, &out_bits);
      QCOMPARE(out_bits, 16);
    }
  }

  void pngQualityIsTheZlibLevel() {
    QVERIFY(write("photo.png", OIIO::TypeDesc::UINT8));
    for (const auto& [quality, level] :
         {std::pair{"10", 0}, std::pair{"50", 1}, std::pair{"95", 3}}) {
      const QString out = path("q") + quality + ".png";
      const auto run = artcamCli(
          {"warp", path("photo.png"), path("lens.artcam"), "-o", out, "-q", "--quality", quality});
      QVERIFY2(run.exit_code == 0, qPrintable(run.err));
      QCOMPARE(pngZlibLevel(out), level);
    }
    QVERIFY(pixels(path("q10.png")) == pixels(path("q95.png")));
    QVERIFY(!pixels(path("q10.png")).empty());
  }
};

QTEST_GUILESS_MAIN(TestCliWriteChoices)
#include "test_cli_write_choices.moc"
