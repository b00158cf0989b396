// SPDX-License-Identifier: Apache-2.0
// artcam lens end to end: search, then a camera from the database, then artcam warp of a photo
// through it, compared with the photo resampled where lfModifier itself says each corrected
// pixel comes from. The photo is an analytic pattern written with OpenImageIO, so the truth is
// the pattern evaluated at lensfun's coordinates, not another resampler; the warp's only
// freedom is its bilinear filter over a pattern smooth at the pixel scale.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QtTest/QtTest>

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <lensfun/lensfun.h>

#include <cmath>
#include <vector>

using artcam::test::artcamCli;

namespace {

constexpr int kW = 600, kH = 400;
const char* const kLens = "Canon PowerShot G11 & compatibles (Standard)";

float pattern(double x, double y) {
  return static_cast<float>(0.5 + 0.4 * std::sin(2 * M_PI * x / 150.0) *
                                      std::cos(2 * M_PI * y / 110.0));
}

bool writePattern(const std::string& path) {
  std::vector<float> px(static_cast<size_t>(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        px[(static_cast<size_t>(y) * kW + x) * 3 + c] = pattern(x + 0.5, y + 0.5);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  const OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::FLOAT);
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
         out->close();
}

QJsonObject json(const QString& text) { return QJsonDocument::fromJson(text.toUtf8()).object(); }

}  // namespace

class TestCliLens : public QObject {
  Q_OBJECT

 private slots:
  void search() {
    const auto r = artcamCli({"lens", "search", "canon", "10-22", "--json"});
    QCOMPARE(r.exit_code, 0);
    const QJsonArray lenses = json(r.out)["lenses"].toArray();
    QVERIFY(!lenses.isEmpty());
    bool found = false;
    for (const auto& l : lenses) {
      const QString model = l.toObject()["model"].toString();
      found = found || model == "Canon EF-S 10-22mm f/3.5-4.5 USM";
      QVERIFY(model.contains("10-22"));
    }
    QVERIFY(found);
    // Words of a lens name split at punctuation ("f/1.4G"): lensfun's own match finds what
    // whole-word beginnings miss. The name is one of Debian's lensfun database (slr-nikon.xml).
    const auto nikon = artcamCli({"lens", "search", "nikon", "50mm", "1.4", "--json"});
    QCOMPARE(nikon.exit_code, 0);
    const QJsonObject nikon_report = json(nikon.out);
    QCOMPARE(nikon_report["match"].toString(), QString("lensfun"));
    bool nikkor = false;
    for (const auto& l : nikon_report["lenses"].toArray()) {
      const QString model = l.toObject()["model"].toString();
      nikkor = nikkor || model == "Nikon AF-S Nikkor 50mm f/1.4G";
      QVERIFY2(model.contains("Nikon") && model.contains("50mm") && model.contains("1.4"),
               qPrintable(model));
    }
    QVERIFY(nikkor);
    const auto nikon_text = artcamCli({"lens", "search", "nikon", "50mm", "1.4"});
    QVERIFY(nikon_text.out.contains("lensfun's own match"));
    QVERIFY(nikon_text.out.contains("Nikon AF-S Nikkor 50mm f/1.4G"));
    const auto none = artcamCli({"lens", "search", "nosuchlensmakerxyz"});
    QCOMPARE(none.exit_code, 0);
    QVERIFY(none.out.contains("no lens"));
  }

  void correctsAsLensfunDoes() {
    QTemporaryDir dir;
    const QString photo = dir.filePath("photo.exr"), cam = dir.filePath("g11.artcam"),
                  out = dir.filePath("corrected.exr");
    QVERIFY(writePattern(photo.toStdString()));
    const auto made = artcamCli({"lens", "camera", "--lens", kLens, "--focal", "6.1", "--size",
                                 "600x400", "-o", cam, "--json"});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
    const QJsonObject report = json(made.out);
    QVERIFY(report["within_tolerance"].toBool());
    QVERIFY(report["max_px"].toDouble() <= 0.5);
    QVERIFY(report["checked"].toInt() > 10000);
    const auto warped = artcamCli({"warp", photo, cam, "-o", out});
    QVERIFY2(warped.exit_code == 0, qPrintable(warped.err));

    auto in = OIIO::ImageInput::open(out.toStdString());
    QVERIFY(in);
    const OIIO::ImageSpec spec = in->spec();
    QCOMPARE(spec.width, kW);
    QCOMPARE(spec.height, kH);
    std::vector<float> px(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    QVERIFY(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    in->close();

    // lensfun, as its documentation says: the modifier's crop is the lens's calibration crop
    // here (no --crop), integer pixel coordinates are pixel centres.
    lfDatabase db;
    QCOMPARE(db.Load(), LF_NO_ERROR);
    const lfLens** lenses = db.FindLenses(nullptr, nullptr, kLens, 0);
    QVERIFY(lenses && lenses[0]);
    const lfLens* lens = lenses[0];
    lfModifier mod(lens, lens->CropFactor, kW, kH);
    mod.Initialize(lens, LF_PF_F32, 6.1f, 8.0f, 1000.0f, 1.0f, LF_RECTILINEAR,
                   LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY, false);
    double sum = 0, worst = 0, unmoved = 0;
    int n = 0;
    for (int y = 2; y < kH - 2; y += 3)
      for (int x = 2; x < kW - 2; x += 3) {
        float s[2];
        mod.ApplyGeometryDistortion(static_cast<float>(x), static_cast<float>(y), 1, 1, s);
        const double sx = s[0] + 0.5, sy = s[1] + 0.5;
        if (sx < 2 || sy < 2 || sx > kW - 2 || sy > kH - 2) continue;
        const float* p = &px[(static_cast<size_t>(y) * kW + x) * spec.nchannels];
        const double d = std::abs(p[1] - pattern(sx, sy));
        sum += d;
        unmoved += std::abs(p[1] - pattern(x + 0.5, y + 0.5));
        worst = std::max(worst, d);
        ++n;
      }
    lf_free(lenses);
    QVERIFY(n > 20000);
    // The pattern's slope is at most 0.023 per pixel: 0.5 px of camera error is 0.012, the
    // bilinear filter's error on it under 0.003.
    QVERIFY2(sum / n < 0.004, qPrintable(QString::number(sum / n)));
    QVERIFY2(worst < 0.02, qPrintable(QString::number(worst)));
    // The map really moves pixels: the photo left as it was is far from lensfun's picture.
    QVERIFY(unmoved > 5 * sum);
  }

  void refusals() {
    QTemporaryDir dir;
    const QString cam = dir.filePath("c.artcam");
    auto r = artcamCli({"lens", "camera", "--lens", "Canon PowerShot G11", "--focal", "6.1",
                        "--size", "600x400", "-o", cam});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("did you mean"));
    QCOMPARE(r.err.trimmed().count('\n'), 0);
    QVERIFY(!QFile::exists(cam));
    r = artcamCli({"lens", "camera", "--lens", kLens, "--size", "600x400", "-o", cam});
    QCOMPARE(r.exit_code, 2);  // no --focal
    QVERIFY(r.err.contains("--focal"));
    r = artcamCli({"lens", "camera", "--lens", kLens, "--focal", "99", "--size", "600x400", "-o",
                   cam});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("6.1-30.5"));
    QFile f(cam);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("keep");
    f.close();
    r = artcamCli({"lens", "camera", "--lens", kLens, "--focal", "6.1", "--size", "600x400", "-o",
                   cam});
    QCOMPARE(r.exit_code, 1);
    QVERIFY(r.err.contains("--overwrite"));
    QVERIFY(f.open(QIODevice::ReadOnly));
    QCOMPARE(f.readAll(), QByteArray("keep"));
    r = artcamCli({"lens", "frobnicate"});
    QCOMPARE(r.exit_code, 2);
  }
};

QTEST_APPLESS_MAIN(TestCliLens)
#include "test_cli_lens.moc"
