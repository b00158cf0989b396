// SPDX-License-Identifier: Apache-2.0
// --edge on warp and batch against Hugin's fulla, which extends the edge: a scale about the
// centre slightly above 1 (fulla's radial polynomial 0:0:0:d with --dont-rescale, the camera
// `lens-distortion --scale 1/d`) puts every border pixel's source in the last half pixel, where
// the three modes differ. extend gives fulla's border within 1/255 and its
// alpha; transparent (the default, which ST maps assume) fades it; black is transparent's colours
// over opaque black. Fails, saying so, when fulla is not installed.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using artcam::test::artcamCli;

namespace {

constexpr int kW = 120, kH = 80;
constexpr double kScale = 0.996;  // target = scale · source about the centre
// 1/255, with room for the float rounding of associating alpha on read.
constexpr double kOneStep = 1.0 + 0.01;

// Premultiplied RGBA floats in 0..255 (OpenImageIO associates a PNG's or TIFF's alpha on
// read); an image without alpha gets 255.
std::vector<double> readRgba(const QString& path) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<float> px(static_cast<size_t>(spec.width * spec.height * spec.nchannels));
  if (spec.width != kW || spec.height != kH ||
      !in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()))
    return {};
  std::vector<double> out(static_cast<size_t>(kW * kH * 4), 255.0);
  for (int p = 0; p < kW * kH; ++p)
    for (int c = 0; c < std::min(4, spec.nchannels); ++c)
      out[static_cast<size_t>(p * 4 + c)] = 255.0 * px[static_cast<size_t>(p * spec.nchannels + c)];
  return out;
}

// The border ring: rows 0 and H−1, columns 0 and W−1.
bool onBorder(int x, int y) { return x == 0 || y == 0 || x == kW - 1 || y == kH - 1; }

struct Difference {
  double colour = 0.0, alpha = 0.0;
};
Difference borderDifference(const std::vector<double>& a, const std::vector<double>& b,
                            bool border = true) {
  Difference d;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (onBorder(x, y) != border) continue;
      const size_t p = static_cast<size_t>((y * kW + x) * 4);
      for (int c = 0; c < 3; ++c) d.colour = std::max(d.colour, std::abs(a[p + c] - b[p + c]));
      d.alpha = std::max(d.alpha, std::abs(a[p + 3] - b[p + 3]));
    }
  return d;
}

}  // namespace

class TestCliEdge : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const char* name) const { return dir_.filePath(name); }
  QString fulla_;

  QString warp(const QString& name, const QStringList& extra) {
    const auto run = artcamCli(QStringList{"warp", path("src.png"), path("scale.artcam"), "-o",
                                           path(name.toUtf8().constData()), "--overwrite", "-q"} +
                               extra);
    return run.exit_code == 0 ? path(name.toUtf8().constData()) : QString("failed: ") + run.err;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    // A colour ramp with a ripple, so every border pixel differs from its neighbours inwards;
    // smooth enough that fulla's interpolator and bilinear agree within 1/255 inside (checked
    // below), so what the border test sees is the edge rule alone.
    OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
    std::vector<unsigned char> px(static_cast<size_t>(kW * kH * 3));
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        unsigned char* p = px.data() + (y * kW + x) * 3;
        p[0] = static_cast<unsigned char>(30 + 200 * x / kW);
        p[1] = static_cast<unsigned char>(20 + 210 * y / kH);
        p[2] = static_cast<unsigned char>(128 + 90 * std::sin(x / 9.0) * std::cos(y / 7.0));
      }
    auto out = OIIO::ImageOutput::create(path("src.png").toStdString());
    QVERIFY(out && out->open(path("src.png").toStdString(), spec) &&
            out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
    const auto made = artcamCli({"preset", "lens-distortion", "--k1", "0", "--k2", "0", "--scale",
                                 QString::number(kScale, 'g', 17), "--size", "120x80", "-o",
                                 path("scale.artcam")});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
    fulla_ = QStandardPaths::findExecutable("fulla");
  }

  void extendMatchesFullasBorder() {
    if (fulla_.isEmpty()) QFAIL("fulla (Debian's hugin-tools) is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QProcess p;
    p.start(fulla_, {"--dont-rescale", "--green=0:0:0:" + QString::number(1.0 / kScale, 'g', 17),
                     "--output=" + path("fulla.tif"), path("src.png")});
    QVERIFY(p.waitForFinished(60000) && p.exitCode() == 0);
    const std::vector<double> fulla = readRgba(path("fulla.tif"));
    QVERIFY(!fulla.empty());

    const std::vector<double> extend = readRgba(warp("extend.png", {"--edge", "extend"}));
    const std::vector<double> by_default = readRgba(warp("default.png", {}));
    const std::vector<double> transparent =
        readRgba(warp("transparent.png", {"--edge", "transparent"}));
    const std::vector<double> black = readRgba(warp("black.png", {"--edge", "black"}));
    QVERIFY(!extend.empty() && !by_default.empty() && !transparent.empty() && !black.empty());

    const Difference inside = borderDifference(extend, fulla, false);
    QVERIFY2(inside.colour <= kOneStep,
             qPrintable(QString("inside the border, bilinear vs fulla: %1").arg(inside.colour)));
    const Difference e = borderDifference(extend, fulla);
    qInfo("border, --edge extend vs fulla: colour %.3f/255, alpha %.3f/255", e.colour, e.alpha);
    QVERIFY2(
        e.colour <= kOneStep && e.alpha <= kOneStep,
        qPrintable(QString("extend vs fulla: colour %1, alpha %2").arg(e.colour).arg(e.alpha)));
    QCOMPARE(borderDifference(by_default, transparent).alpha, 0.0);  // the default
    // Transparent fades the border fulla keeps opaque; black is that over opaque black.
    const Difference t = borderDifference(transparent, fulla);
    QVERIFY2(t.alpha > 50.0,
             qPrintable(QString("transparent's border alpha differs by %1").arg(t.alpha)));
    const Difference b = borderDifference(black, transparent);
    QVERIFY2(b.colour <= kOneStep,
             qPrintable(QString("black vs transparent colour %1").arg(b.colour)));
    double black_alpha = 255.0;
    for (size_t k = 3; k < black.size(); k += 4) black_alpha = std::min(black_alpha, black[k]);
    QCOMPARE(black_alpha, 255.0);
  }

  // batch takes the same option and writes the same pixels as warp.
  void batchTakesTheSameEdge() {
    const std::vector<double> warped = readRgba(warp("w.png", {"--edge", "transparent"}));
    const auto run = artcamCli({"batch", path("scale.artcam"), path("src.png"), "-o", path("out"),
                                "--edge", "transparent", "-q"});
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    const std::vector<double> batched = readRgba(path("out/src.png"));
    QVERIFY(!warped.empty() && !batched.empty());
    QVERIFY(warped == batched);
  }

  // One line naming the option and the values, then the commands' usual pointer to --help.
  void anUnknownModeIsRefusedInOneLine() {
    for (const char* command : {"warp", "batch"}) {
      const QStringList args =
          QString(command) == "warp"
              ? QStringList{"warp", path("src.png"), path("scale.artcam"), "-o", path("x.png")}
              : QStringList{"batch", path("scale.artcam"), path("src.png"), "-o", path("x")};
      const auto run = artcamCli(args + QStringList{"--edge", "wrap"});
      QCOMPARE(run.exit_code, 2);
      QVERIFY2(run.err.contains("--edge expects transparent, extend or black"),
               qPrintable(run.err));
      QCOMPARE(run.err.trimmed().count('\n'), 1);
      QVERIFY2(run.err.contains("--help"), qPrintable(run.err));
    }
  }
};

QTEST_GUILESS_MAIN(TestCliEdge)
#include "test_cli_edge.moc"
