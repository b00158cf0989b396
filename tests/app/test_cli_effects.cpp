// SPDX-License-Identifier: Apache-2.0
// The effect presets through the public CLI (artcam preset … ; artcam warp … --depth FILE), run
// as processes on the bundled photo. Expectations are the effects' neutral settings, which must
// give back the photo (to 8-bit rounding): zero colour shift, aerial perspective at the near
// depth, depth of field at the focus depth; and refusals naming their cause.
#include "core/io/artcam_file.h"
#include "tests/support/test_support.h"

#include <OpenImageIO/imagebuf.h>

#include <QtTest/QtTest>

#include <QProcess>
#include <QTemporaryDir>

#include <cmath>
#include <cstdlib>
#include <vector>

namespace {

struct Run {
  int exit_code = -1;
  QString out;
  QString err;
};

Run artcamCli(const QStringList& args) {
  QProcess p;
  p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
  p.waitForFinished(300000);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
          QString::fromUtf8(p.readAllStandardOutput()), QString::fromUtf8(p.readAllStandardError())};
}

// Largest difference in 8-bit levels between two images' RGB, over pixels `margin` from the edge.
int maxLevelDifference(const QString& a, const QString& b, int margin) {
  OIIO::ImageBuf x(a.toStdString()), y(b.toStdString());
  if (!x.read(0, 0, true, OIIO::TypeDesc::FLOAT) || !y.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return 999;
  if (x.spec().width != y.spec().width || x.spec().height != y.spec().height) return 998;
  int worst = 0;
  for (int j = margin; j < x.spec().height - margin; ++j)
    for (int i = margin; i < x.spec().width - margin; ++i)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, static_cast<int>(std::lround(255.0 * std::abs(x.getchannel(i, j, 0, c) - y.getchannel(i, j, 0, c)))));
  return worst;
}

// Largest difference in LINEAR light (sRGB decoded) between two 8-bit images' RGB.
double maxLinearDifference(const QString& a, const QString& b) {
  OIIO::ImageBuf x(a.toStdString()), y(b.toStdString());
  if (!x.read(0, 0, true, OIIO::TypeDesc::FLOAT) || !y.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return 999;
  const auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  double worst = 0;
  for (int j = 0; j < x.spec().height; ++j)
    for (int i = 0; i < x.spec().width; ++i)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(linear(x.getchannel(i, j, 0, c)) - linear(y.getchannel(i, j, 0, c))));
  return worst;
}

bool writeConstantDepth(const QString& path, int w, int h, float value) {
  OIIO::ImageSpec spec(w, h, 1, OIIO::TypeDesc::FLOAT);
  OIIO::ImageBuf buf(spec);
  std::vector<float> v(static_cast<size_t>(w) * static_cast<size_t>(h), value);
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, v.data());
  return buf.write(path.toStdString());
}

}  // namespace

class TestCliEffects : public QObject {
  Q_OBJECT

 private slots:
  void neutralSettingsGiveThePhotoBack() {
    QTemporaryDir dir;
    const QString photo = QString::fromStdString(artcam::test::resourcePath("coffee.png"));
    const QString cam = dir.filePath("cs.artcam"), out = dir.filePath("cs.png");
    Run r = artcamCli({"preset", "colour-shift", "--s-red", "0", "--s-blue", "0", "-o", cam});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", photo, cam, "-o", out});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("splat"), qPrintable(r.out));
    QVERIFY(maxLevelDifference(photo, out, 2) <= 1);

    const QString depth = dir.filePath("near.exr");
    QVERIFY(writeConstantDepth(depth, 600, 400, 1.0f));
    r = artcamCli({"preset", "aerial-perspective", "-o", dir.filePath("ap.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", photo, dir.filePath("ap.artcam"), "-o", dir.filePath("ap.png"), "--depth", depth});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    // At the near depth l = 0 up to the log fit's error (≤ 0.0065 over [1, 100], times the
    // strength 0.7), plus 8-bit rounding (≤ 0.0045 in linear light near white).
    const double ap = maxLinearDifference(photo, dir.filePath("ap.png"));
    QVERIFY2(ap <= 0.7 * 0.0065 + 0.0046, qPrintable(QString("linear difference %1").arg(ap)));

    const QString focus = dir.filePath("focus.exr");
    QVERIFY(writeConstantDepth(focus, 300, 200, 2.0f));  // half size: read at the same place
    r = artcamCli({"preset", "depth-of-field", "--focus", "2", "-o", dir.filePath("dof.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", photo, dir.filePath("dof.artcam"), "-o", dir.filePath("dof.png"), "--depth", focus});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY(maxLevelDifference(photo, dir.filePath("dof.png"), 0) <= 1);
  }

  void depthEffectsWithoutDepthAreRefused() {
    QTemporaryDir dir;
    const QString photo = QString::fromStdString(artcam::test::resourcePath("coffee.png"));
    Run r = artcamCli({"preset", "aerial-perspective", "-o", dir.filePath("ap.artcam")});
    QCOMPARE(r.exit_code, 0);
    r = artcamCli({"warp", photo, dir.filePath("ap.artcam"), "-o", dir.filePath("ap.png")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("--depth"), qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("ap.png")));
  }

  // A value outside the table's range is a usage error (exit 2) whose first line names the
  // option and the range; a value the camera refuses (near ≥ far) is a command error (exit 1).
  // Neither writes a file.
  void outOfRangeValuesAreRefused() {
    QTemporaryDir dir;
    const QString out = dir.filePath("b.artcam");
    Run r = artcamCli({"preset", "barrel", "--k", "0.9", "-o", out});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.section('\n', 0, 0).contains("--k = 0.9 is outside its range -1 … 0"), qPrintable(r.err));
    r = artcamCli({"preset", "aerial-perspective", "--haze", "0.5,1.5,0.5", "-o", out});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.section('\n', 0, 0).contains("--haze = 1.5 is outside its range 0 … 1"), qPrintable(r.err));
    r = artcamCli({"preset", "aerial-perspective", "--haze", "0.5,0.5", "-o", out});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("--haze expects 3 comma-separated numbers"), qPrintable(r.err));
    r = artcamCli({"preset", "aerial-perspective", "--near", "50", "--far", "10", "-o", out});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("near"), qPrintable(r.err));
    QVERIFY(!QFile::exists(out));
    // The ends of a range are inside it, and the frame may be given as WxH or W,H.
    r = artcamCli({"preset", "pincushion", "--k", "0.45", "--size", "300,300", "-o", out});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"preset", "inverse-perspective", "--gain", "-0.85", "--size", "200x400", "-o", out, "--overwrite"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
  }

  // --thin-lens picks the depth-of-field stage (depth_of_field.h): the written camera's σ² at a
  // few depths against k²(d − f)²/d² (thin lens, the default) and k²(d − f)²/f² (linear).
  void depthOfFieldLensModels() {
    QTemporaryDir dir;
    const double f = 2.0, k = 0.02;
    for (const double gamma : {1.0, 0.0}) {
      QStringList args = {"preset", "depth-of-field", "--focus", "2", "--blur", "0.02", "-o",
                          dir.filePath("dof.artcam"), "--overwrite"};
      if (gamma == 0.0) args << "--thin-lens" << "0";
      const Run r = artcamCli(args);
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      const auto doc = artcam::readArtcam(dir.filePath("dof.artcam").toStdString());
      QVERIFY2(doc.ok(), doc.status.message.c_str());
      for (const double d : {0.5, 1.0, 3.0, 40.0}) {
        Eigen::VectorXd x(9);
        x << 0.0, 0.0, 1, 0.5, 0.5, 0.5, 1, d, 1;
        const double den = gamma == 1.0 ? d : f;
        const double expected = k * k * (d - f) * (d - f) / (den * den);
        QVERIFY(std::abs(doc.value->main().evaluate(x)[7] - expected) <= 1e-12);
      }
    }
    const Run bad = artcamCli({"preset", "depth-of-field", "--thin-lens", "2", "-o", dir.filePath("bad.artcam")});
    QCOMPARE(bad.exit_code, 2);  // outside the table's range 0 … 1
    QVERIFY2(bad.err.contains("thin-lens"), qPrintable(bad.err));
  }

  // The plain effect names are the image presets (position block (u, v, 1), a photo frame); the
  // paper's Fig 1 point-cloud versions end in -3d (position (X, Y, Z, 1), no frame). The radial
  // lenses also against their closed form u' = u/(1 − k r²) in the normalised frame.
  void issueNamesAreImagePresets() {
    QTemporaryDir dir;
    const QString out = dir.filePath("p.artcam");
    for (const char* name : {"barrel", "pincushion", "twist", "inverse-perspective", "chromatic-aberration",
                             "colour-shift", "aerial-perspective", "depth-of-field"}) {
      const Run r = artcamCli({"preset", name, "-o", out, "--overwrite"});
      QVERIFY2(r.exit_code == 0, qPrintable(QString(name) + ": " + r.err));
      const auto doc = artcam::readArtcam(out.toStdString());
      QVERIFY2(doc.ok(), doc.status.message.c_str());
      QCOMPARE(doc.value->main().blocks().front().size, 3);
      QVERIFY2(doc.value->main().sourceSize().isImage(), name);
    }
    for (const char* name : {"twist-3d", "pincushion-3d", "inverse-perspective-3d", "chromatic-aberration-3d"}) {
      const Run r = artcamCli({"preset", name, "-o", out, "--overwrite"});
      QVERIFY2(r.exit_code == 0, qPrintable(QString(name) + ": " + r.err));
      const auto doc = artcam::readArtcam(out.toStdString());
      QVERIFY2(doc.ok(), doc.status.message.c_str());
      QCOMPARE(doc.value->main().blocks().front().size, 4);
    }
    QCOMPARE(artcamCli({"preset", "twist-2d", "-o", out}).exit_code, 2);  // the old names are gone
    for (const double k : {0.15, -0.2}) {
      const Run r = artcamCli({"preset", k > 0 ? "pincushion" : "barrel", "--k", QString::number(k),
                               "-o", out, "--overwrite"});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      const auto doc = artcam::readArtcam(out.toStdString());
      QVERIFY2(doc.ok(), doc.status.message.c_str());
      const double u = 0.3, v = -0.2, g = 1.0 / (1.0 - k * (u * u + v * v));
      Eigen::VectorXd x(3);
      x << u, v, 1;
      const Eigen::VectorXd y = doc.value->main().evaluate(x);
      QVERIFY(std::abs(y[0] - u * g) < 1e-12 && std::abs(y[1] - v * g) < 1e-12);
    }
  }

  // The 3D effects' parameters are in the object frame (effects_3d_table.h): by default the
  // origin and radius 1, so the numbers are object units; --object-centre C --object-radius R
  // move the same effect to c + R · E((P − c)/R). Out-of-range values and radii are refused.
  void threeDPresetsInTheObjectFrame() {
    QTemporaryDir dir;
    const auto moved = [&](const QStringList& options, const Eigen::Vector3d& p) -> Eigen::Vector3d {
      const QString out = dir.filePath("swell.artcam");
      const Run r = artcamCli(QStringList{"preset", "pincushion-3d"} + options +
                              QStringList{"-o", out, "--overwrite"});
      if (r.exit_code != 0) return Eigen::Vector3d::Constant(std::nan(""));
      const auto doc = artcam::readArtcam(out.toStdString());
      if (!doc.ok()) return Eigen::Vector3d::Constant(std::nan(""));
      return doc.value->main().evaluate(Eigen::Vector4d(p.x(), p.y(), p.z(), 1)).head<3>();
    };
    const Eigen::Vector3d local(0.5, -0.2, 0.1);
    const Eigen::Vector3d swollen = local / (1.0 - 0.12 * local.squaredNorm());  // k = 0.12
    QVERIFY((moved({}, local) - swollen).norm() < 1e-12);
    const Eigen::Vector3d c(1, 2, 3);
    const Eigen::Vector3d world =
        moved({"--object-centre", "1,2,3", "--object-radius", "2"}, c + 2 * local);
    QVERIFY2((world - (c + 2 * swollen)).norm() < 1e-12, "the frame's rule");
    const Run zero =
        artcamCli({"preset", "twist-3d", "--object-radius", "0", "-o", dir.filePath("z.artcam")});
    QCOMPARE(zero.exit_code, 2);
    QVERIFY2(zero.err.contains("--object-radius"), qPrintable(zero.err));
    const Run wide =
        artcamCli({"preset", "pincushion-3d", "--k", "5", "-o", dir.filePath("w.artcam")});
    QCOMPARE(wide.exit_code, 2);
    QVERIFY2(wide.err.contains("k = 5 is outside its range"), qPrintable(wide.err));
    const Run list = artcamCli({"preset", "list"});
    QVERIFY2(list.out.contains("object-radius=1"), qPrintable(list.out));
  }

  void chromaticAberrationWritesThreeLayers() {
    QTemporaryDir dir;
    const QString photo = QString::fromStdString(artcam::test::resourcePath("coffee.png"));
    Run r = artcamCli({"preset", "chromatic-aberration", "--red", "0.01", "-o", dir.filePath("ca.artcam")});
    QCOMPARE(r.exit_code, 0);
    QFile f(dir.filePath("ca.artcam"));
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(f.readAll().contains("\"layers\""));
    r = artcamCli({"warp", photo, dir.filePath("ca.artcam"), "-o", dir.filePath("ca.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("layered"), qPrintable(r.out));
    // Red moved, green did not: the two differ from the photo by different amounts.
    QVERIFY(maxLevelDifference(photo, dir.filePath("ca.png"), 8) > 3);
  }
};

QTEST_GUILESS_MAIN(TestCliEffects)
#include "test_cli_effects.moc"
