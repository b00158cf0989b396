// SPDX-License-Identifier: Apache-2.0
// Lenses from the photo: `artcam lens camera --from PHOTO` and `artcam batch --lens-from-exif`.
// The photos are made here with OpenImageIO, which writes their EXIF (Make, Model, LensModel,
// FocalLength) — a writer other than the exiv2 reader under test. The truths: lensfun itself
// says which camera the EXIF names and its crop factor (lfDatabase::FindCamerasExt in the
// test), and `artcam lens camera --lens NAME --focal MM --size WxH --crop C` followed by
// `artcam warp`, the path a user takes by hand, says what each frame must become.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imageio.h>

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <lensfun/lensfun.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

using artcam::test::artcamCli;

namespace {

constexpr int kW = 300, kH = 200;
const char* const kMaker = "Canon";
const char* const kModel = "Canon PowerShot G11";
const char* const kLens = "Canon PowerShot G11 & compatibles (Standard)";

struct Exif {
  QString maker = kMaker;
  QString model = kModel;
  QString lens = "6.1-30.5 mm";  // what the G11 writes: its range, not a lensfun name
  double focal_mm = 6.1;
};

// A smooth pattern (so warps of it differ visibly when the camera differs) as an 8-bit JPEG.
bool writePhoto(const QString& path, const std::optional<Exif>& exif) {
  std::vector<unsigned char> px(static_cast<size_t>(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        px[(static_cast<size_t>(y) * kW + x) * 3 + c] = static_cast<unsigned char>(
            127.5 + 100 * std::sin(2 * M_PI * (x + 13 * c) / 37.0) * std::cos(2 * M_PI * y / 29.0));
  auto out = OIIO::ImageOutput::create(path.toStdString());
  if (!out) return false;
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("CompressionQuality", 95);
  if (exif) {
    if (!exif->maker.isEmpty()) spec.attribute("Make", exif->maker.toStdString());
    if (!exif->model.isEmpty()) spec.attribute("Model", exif->model.toStdString());
    if (!exif->lens.isEmpty()) spec.attribute("Exif:LensModel", exif->lens.toStdString());
    if (exif->focal_mm > 0) spec.attribute("Exif:FocalLength", static_cast<float>(exif->focal_mm));
  }
  return out->open(path.toStdString(), spec) &&
         out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close();
}

std::vector<float> pixels(const QString& path, int* width = nullptr, int* height = nullptr) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<float> px(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data())) return {};
  if (width) *width = spec.width;
  if (height) *height = spec.height;
  return px;
}

double maxDifference(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size() || a.empty()) return 1e9;
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

// lensfun's own answer for the EXIF camera: its crop factor.
double lensfunCrop() {
  lfDatabase db;
  if (db.Load() != LF_NO_ERROR) return 0;
  const lfCamera** cameras = db.FindCamerasExt(kMaker, kModel, 0);
  const double crop = cameras && cameras[0] ? cameras[0]->CropFactor : 0;
  lf_free(cameras);
  return crop;
}

QJsonObject json(const QString& text) { return QJsonDocument::fromJson(text.toUtf8()).object(); }

}  // namespace

class TestCliLensExif : public QObject {
  Q_OBJECT

 private slots:
  // --from takes lens, focal length, crop and size from the photo: the camera it writes is the
  // one named by hand with lensfun's answers.
  void cameraFromPhoto() {
    QTemporaryDir dir;
    const QString photo = dir.filePath("g11.jpg");
    Exif exif;
    exif.focal_mm = 12.0;
    QVERIFY(writePhoto(photo, exif));
    const double crop = lensfunCrop();
    QVERIFY(crop > 1);
    const QString from = dir.filePath("from.artcam"), by_hand = dir.filePath("hand.artcam");
    const auto made = artcamCli({"lens", "camera", "--from", photo, "-o", from, "--json"});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
    const QJsonObject report = json(made.out);
    QCOMPARE(report["lens"].toObject()["model"].toString(), QString(kLens));
    QCOMPARE(report["focal_mm"].toDouble(), 12.0);
    QCOMPARE(report["crop"].toDouble(), crop);
    QCOMPARE(report["size"].toArray()[0].toInt(), kW);
    QCOMPARE(report["size"].toArray()[1].toInt(), kH);
    QVERIFY(report["camera"].toString().contains("G11"));
    const auto hand = artcamCli({"lens", "camera", "--lens", kLens, "--focal", "12", "--size",
                                 QString("%1x%2").arg(kW).arg(kH), "--crop",
                                 QString::number(crop, 'g', 17), "-o", by_hand});
    QVERIFY2(hand.exit_code == 0, qPrintable(hand.err));
    QFile a(from), b(by_hand);
    QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly));
    QCOMPARE(a.readAll(), b.readAll());
    // The text report names the photo and what its EXIF chose.
    const auto text = artcamCli({"lens", "camera", "--from", photo, "-o", from, "--overwrite"});
    QVERIFY2(text.exit_code == 0, qPrintable(text.err));
    QVERIFY2(text.out.contains(photo) && text.out.contains(QString(kLens) + " at 12 mm"),
             qPrintable(text.out));
  }

  void refusals() {
    QTemporaryDir dir;
    const QString cam = dir.filePath("c.artcam");
    auto oneLine = [&](const QStringList& args, int code, const QStringList& needles) {
      const auto r = artcamCli(args);
      QVERIFY2(r.exit_code == code, qPrintable(QString::number(r.exit_code) + " " + r.err));
      // One line (a usage error adds the pointer to --help on a second).
      QVERIFY2(r.err.trimmed().count('\n') == (code == 2 ? 1 : 0), qPrintable(r.err));
      for (const QString& n : needles) QVERIFY2(r.err.contains(n), qPrintable(r.err));
      QVERIFY(!QFile::exists(cam));
    };
    const QString bare = dir.filePath("bare.jpg");
    QVERIFY(writePhoto(bare, std::nullopt));
    oneLine({"lens", "camera", "--from", bare, "-o", cam}, 1, {bare, "EXIF"});
    Exif no_focal;
    no_focal.focal_mm = 0;
    const QString unfocused = dir.filePath("nofocal.jpg");
    QVERIFY(writePhoto(unfocused, no_focal));
    oneLine({"lens", "camera", "--from", unfocused, "-o", cam}, 1, {unfocused, "focal length"});
    Exif unknown;
    unknown.maker = "Acme";
    unknown.model = "Acme Zorp 9";
    unknown.lens = "Zorpinar 50mm";  // "50mm" alone must not pick some 50 mm lens
    unknown.focal_mm = 50;
    const QString odd = dir.filePath("unknown.jpg");
    QVERIFY(writePhoto(odd, unknown));
    oneLine({"lens", "camera", "--from", odd, "-o", cam}, 1,
            {odd, "Zorpinar 50mm", "Acme Zorp 9", "lensfun"});
    oneLine({"lens", "camera", "--from", odd, "--focal", "7", "-o", cam}, 2, {"--focal", "--from"});
    oneLine({"lens", "camera", "--from", dir.filePath("missing.jpg"), "-o", cam}, 1,
            {"missing.jpg"});
    // The camera never replaces the photo it was read from.
    const QString good = dir.filePath("good.jpg");
    QVERIFY(writePhoto(good, Exif{}));
    const qint64 size = QFileInfo(good).size();
    const auto over = artcamCli({"lens", "camera", "--from", good, "-o", good, "--overwrite"});
    QVERIFY(over.exit_code != 0);
    QVERIFY2(over.err.contains(good), qPrintable(over.err));
    QCOMPARE(QFileInfo(good).size(), size);
  }

  // The done-when figure: one zoom shoot at three focal lengths (6.1 mm twice) corrected by one
  // `batch --lens-from-exif`, each output equal to `lens camera` for its focal length then
  // `warp`, and one camera made per distinct focal length.
  void batchZoomShoot() {
    QTemporaryDir dir;
    const std::vector<double> focals = {6.1, 12.0, 6.1, 30.5};
    QStringList inputs;
    QDir().mkpath(dir.filePath("shoot"));
    for (size_t i = 0; i < focals.size(); ++i) {
      Exif exif;
      exif.focal_mm = focals[i];
      inputs << dir.filePath(QString("shoot/frame%1.jpg").arg(i));
      QVERIFY(writePhoto(inputs.back(), exif));
    }
    // One frame whose EXIF gives no lens camera fails alone, naming itself.
    const QString bare = dir.filePath("shoot/bare.jpg");
    QVERIFY(writePhoto(bare, std::nullopt));
    const QString out = dir.filePath("fixed");
    const auto batch = artcamCli(QStringList{"batch", "--lens-from-exif"} + inputs +
                                 QStringList{bare} + QStringList{"-o", out, "--json", "--quiet"});
    QCOMPARE(batch.exit_code, 1);  // the bare frame
    QVERIFY2(batch.err.contains(bare), qPrintable(batch.err));
    const QJsonObject report = json(batch.out);
    const std::set<double> distinct(focals.begin(), focals.end());
    QCOMPARE(report["totals"].toObject()["lens_cameras"].toInt(), int(distinct.size()));
    QCOMPARE(report["totals"].toObject()["written"].toInt(), int(focals.size()));
    const QJsonArray files = report["files"].toArray();
    QCOMPARE(files.size(), inputs.size() + 1);
    QCOMPARE(files.last().toObject()["status"].toString(), QString("failed"));

    const double crop = lensfunCrop();
    std::map<double, int> camera_of_focal;
    for (int i = 0; i < inputs.size(); ++i) {
      const QJsonObject f = files[i].toObject();
      QCOMPARE(f["status"].toString(), QString("written"));
      const QJsonObject lens = f["lens"].toObject();
      QCOMPARE(lens["model"].toString(), QString(kLens));
      QVERIFY(std::abs(lens["focal_mm"].toDouble() - focals[size_t(i)]) < 1e-4);
      // Frames at one focal length share their camera, and only they.
      const int number = lens["camera_number"].toInt();
      const auto [at, fresh] = camera_of_focal.emplace(focals[size_t(i)], number);
      QCOMPARE(at->second, number);
      if (fresh)
        for (const auto& [focal, n] : camera_of_focal)
          if (focal != focals[size_t(i)]) QVERIFY(n != number);

      const QString cam = dir.filePath(QString("by_hand%1.artcam").arg(i)),
                    warped = dir.filePath(QString("by_hand%1.jpg").arg(i));
      const auto made =
          artcamCli({"lens", "camera", "--lens", kLens, "--focal",
                     QString::number(focals[size_t(i)]), "--size", QString("%1x%2").arg(kW).arg(kH),
                     "--crop", QString::number(crop, 'g', 17), "-o", cam});
      QVERIFY2(made.exit_code == 0, qPrintable(made.err));
      const auto warp = artcamCli({"warp", inputs[i], cam, "-o", warped});
      QVERIFY2(warp.exit_code == 0, qPrintable(warp.err));
      const std::vector<float> expected = pixels(warped), got = pixels(f["output"].toString());
      QVERIFY(!expected.empty());
      QVERIFY2(maxDifference(expected, got) <= 1.0 / 255 + 1e-6,
               qPrintable(QString::number(maxDifference(expected, got) * 255)));
      // The correction moves pixels: more than a JPEG round trip does.
      QVERIFY2(maxDifference(pixels(inputs[i]), got) > 6.0 / 255,
               qPrintable(QString::number(maxDifference(pixels(inputs[i]), got) * 255)));
    }
    // Distinct focal lengths give distinct corrections.
    QVERIFY(maxDifference(pixels(files[0].toObject()["output"].toString()),
                          pixels(files[3].toObject()["output"].toString())) > 10.0 / 255);

    // The text form names each frame's lens and focal length, and the cameras made.
    const auto text = artcamCli(QStringList{"batch", "--lens-from-exif"} + inputs +
                                QStringList{"-o", out, "--overwrite"});
    QVERIFY2(text.exit_code == 0, qPrintable(text.err));
    const QString all = text.out + text.err;
    QVERIFY2(all.contains(QString(kLens) + " at 30.5 mm"), qPrintable(all));
    QVERIFY2(all.contains(QString(kLens) + " at 12 mm"), qPrintable(all));
    QVERIFY2(text.out.contains("3 lens cameras made"), qPrintable(text.out));
  }
};

QTEST_APPLESS_MAIN(TestCliLensExif)
#include "test_cli_lens_exif.moc"
