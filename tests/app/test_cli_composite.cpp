// SPDX-License-Identifier: Apache-2.0
// Compositing through the public CLI: `artcam preset composite --op NAME` writes the camera and
// `artcam warp A CAM --second B` renders it. Two float EXR images are made here; the output,
// read back, equals the operator's Porter–Duff formula computed here from the two inputs as the
// reader gives them (linear, premultiplied), divided by eq 5, to 1e-6. A compositing camera
// without --second, and an unknown operator, are refused in one line.
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "tests/support/porter_duff.h"

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <Eigen/Core>

#include <algorithm>
#include <random>

using artcam::test::artcamCli;
using artcam::test::CliRun;

namespace {

using Colour = Eigen::Vector4d;

artcam::ImageF randomImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), alpha(0.05f, 1.0f);
  artcam::ImageF image(w, h, 4, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = image.pixel(x, y);
      const float a = alpha(rng);
      for (int k = 0; k < 3; ++k) p[k] = a * unit(rng);
      p[3] = a;
    }
  return image;
}

Colour pixelOf(const artcam::ImageF& image, int x, int y) {
  const float* p = image.pixel(x, y);
  return {p[0], p[1], p[2], image.alpha_channel >= 0 ? p[image.alpha_channel] : 1.0f};
}

bool oneLine(const QString& text) { return text.trimmed().count('\n') == 0 && !text.trimmed().isEmpty(); }

}  // namespace

class TestCliComposite : public QObject {
  Q_OBJECT

 private slots:
  void warpWithSecondImageIsTheFormula() {
    QTemporaryDir dir;
    const QString a_path = dir.filePath("a.exr"), b_path = dir.filePath("b.exr");
    artcam::WriteImageOptions write;
    write.pixel_type = "float";
    QVERIFY(artcam::writeImage(a_path.toStdString(), randomImage(9, 6, 5), nullptr, write).ok);
    QVERIFY(artcam::writeImage(b_path.toStdString(), randomImage(9, 6, 6), nullptr, write).ok);
    const QString cam = dir.filePath("cam.artcam"), out = dir.filePath("out.exr");
    CliRun r = artcamCli({"preset", "composite", "--op", "multiply", "--amount", "0.8", "--size",
                          "9x6", "-o", cam});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", a_path, cam, "--second", b_path, "-o", out});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));

    const auto a = artcam::readImage(a_path.toStdString());
    const auto b = artcam::readImage(b_path.toStdString());
    const auto o = artcam::readImage(out.toStdString());
    QVERIFY(a.ok() && b.ok() && o.ok());
    QCOMPARE(o->image.width, 9);
    QCOMPARE(o->image.height, 6);
    QVERIFY(o->image.alpha_channel >= 0);
    double worst = 0;
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 9; ++x) {
        const Colour ca = pixelOf(a->image, x, y), cb = pixelOf(b->image, x, y);
        const Colour z = 0.2 * ca + 0.8 * artcam::test::porterDuff(artcam::CompositeOp::Multiply, ca, cb);
        const double alpha = std::min(z[3], 1.0);  // eq 5
        const Colour want(z[0] / z[3] * alpha, z[1] / z[3] * alpha, z[2] / z[3] * alpha, alpha);
        worst = std::max(worst, (pixelOf(o->image, x, y) - want).cwiseAbs().maxCoeff());
      }
    QVERIFY2(worst < 1e-6, qPrintable(QString::number(worst)));

    // info says what the camera reads.
    r = artcamCli({"info", cam});
    QVERIFY(r.exit_code == 0 && r.out.contains("second-colour") && r.out.contains("--second"));
  }

  void refusals() {
    QTemporaryDir dir;
    const QString a_path = dir.filePath("a.exr"), cam = dir.filePath("over.artcam");
    artcam::WriteImageOptions write;
    write.pixel_type = "float";
    QVERIFY(artcam::writeImage(a_path.toStdString(), randomImage(4, 3, 7), nullptr, write).ok);
    CliRun r = artcamCli({"preset", "composite", "--size", "4x3", "-o", cam});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(r.out.contains("op=over"));
    r = artcamCli({"warp", a_path, cam, "-o", dir.filePath("o.exr")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(oneLine(r.err) && r.err.contains("over.artcam") && r.err.contains("--second"),
             qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("o.exr")));
    r = artcamCli({"preset", "composite", "--op", "overlay", "-o", dir.filePath("x.artcam")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("overlay") && r.err.contains("over|under"), qPrintable(r.err));
    r = artcamCli({"preset", "composite", "--amount", "1.5", "-o", dir.filePath("x.artcam")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("amount"), qPrintable(r.err));
  }
};

QTEST_GUILESS_MAIN(TestCliComposite)
#include "test_cli_composite.moc"
