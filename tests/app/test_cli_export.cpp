// SPDX-License-Identifier: Apache-2.0
// artcam export on the bundled project and on damaged ones: the camera and depth it writes are
// the project's (two effects, depth of field last: a blur-variance camera; the painted depths),
// options are checked, and every refusal is one or two lines naming the file and the cause,
// with no output left behind and no input touched.
#include "core/io/artcam_file.h"
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <tuple>

#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <OpenImageIO/imageio.h>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

QByteArray hashOf(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QCryptographicHash::hash(f.readAll(), QCryptographicHash::Sha256);
}

}  // namespace

class TestCliExport : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    for (const char* f : {"coffee.png", "depth-effects.artcamproj"})
      QVERIFY(QFile::copy(QString(ARTCAM_RESOURCES_DIR) + "/" + f, dir_.filePath(f)));
    project_ = dir_.filePath("depth-effects.artcamproj");
  }

  void rendersTheProjectWithItsCameraAndDepth() {
    const QString out = dir_.filePath("out.jpg");
    const Run r = artcamCli({"export", project_, "-o", out, "--quality", "90", "--json", "-q",
                             "--camera-out", dir_.filePath("cam.artcam"), "--depth-out",
                             dir_.filePath("depth.exr")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["width"].toInt(), 600);
    QCOMPARE(j["height"].toInt(), 400);
    QCOMPARE(j["effects"].toInt(), 2);
    QCOMPARE(j["effects_applied"].toInt(), 2);
    QVERIFY2(j["description"].toString().contains("depth-of-field blur"), qPrintable(r.out));
    const auto cam = readArtcam(dir_.filePath("cam.artcam").toStdString());
    QVERIFY2(cam.ok(), cam.status.message.c_str());
    QCOMPARE(cam->depth_output, DepthOutput::BlurVariance);  // depth of field came last
    QVERIFY(readsDepth(*cam));
    // The table plane: 0.6 at the bottom row's anchors, 2.5 at the top anchor; the cup: 0.8.
    const auto depth = readImage(dir_.filePath("depth.exr").toStdString());
    QVERIFY(depth.ok());
    QVERIFY(std::abs(depth->image.pixel(20, 390)[0] - 0.6f) < 1e-4f);
    QVERIFY(std::abs(depth->image.pixel(300, 5)[0] - 2.5f) < 1e-3f);
    QVERIFY(std::abs(depth->image.pixel(290, 140)[0] - 0.8f) < 1e-5f);
    // Its one channel is named Z, as compositors name depth, and warp --depth reads it.
    {
      auto in = OIIO::ImageInput::open(dir_.filePath("depth.exr").toStdString());
      QVERIFY(in);
      QCOMPARE(in->spec().nchannels, 1);
      QCOMPARE(in->spec().channelnames.at(0), std::string("Z"));
      in->close();
      const auto as_depth = readDepthFile(dir_.filePath("depth.exr").toStdString());
      QVERIFY2(as_depth.ok(), as_depth.status.message.c_str());
      QVERIFY(std::abs(as_depth->pixel(290, 140)[0] - 0.8f) < 1e-5f);
    }
    const auto image = readImage(out.toStdString());
    QVERIFY(image.ok());
    QCOMPARE(image->info.format_name, std::string("jpeg"));
    // The far table is hazed towards the haze colour (brighter and bluer than the photo), the
    // cup at 0.8 much less: aerial perspective reached the output.
    const auto photo = readImage(dir_.filePath("coffee.png").toStdString());
    QVERIFY(photo.ok());
    const float* far_out = image->image.pixel(560, 20);
    const float* far_in = photo->image.pixel(560, 20);
    QVERIFY2(far_out[2] > far_in[2] + 0.05f, qPrintable(QString("%1 vs %2").arg(far_out[2]).arg(far_in[2])));
  }

  void aDepthMapOfAnotherAspectIsSaid() {
    // The project's depth map drives depth of field: one of another shape than the photo is
    // stretched, and said to be, as `warp --depth` says it; one of the photo's aspect is not.
    QFile in(project_);
    QVERIFY(in.open(QIODevice::ReadOnly));
    QJsonObject doc = QJsonDocument::fromJson(in.readAll()).object();
    const auto exportWithMap = [&](int width, int height) {
      ImageF depth(width, height, 1);
      std::fill(depth.data.begin(), depth.data.end(), 1.5f);
      const QString map = dir_.filePath(QString("map-%1x%2.exr").arg(width).arg(height));
      if (!writeImage(map.toStdString(), depth).ok) return Run{};
      QJsonObject depth_part;
      depth_part["layers"] = QJsonArray();
      depth_part["map"] = QJsonObject{{"path", map}};
      doc["depth"] = depth_part;
      const QString project = dir_.filePath("map.artcamproj");
      QFile f(project);
      if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) return Run{};
      f.write(QJsonDocument(doc).toJson());
      f.close();
      return artcamCli({"export", project, "-o", dir_.filePath("map.png"), "--overwrite"});
    };
    const Run same = exportWithMap(60, 40);
    QVERIFY2(same.exit_code == 0, qPrintable(same.err));
    QVERIFY2(!same.err.contains("aspect"), qPrintable(same.err));
    const Run wide = exportWithMap(80, 20);
    QVERIFY2(wide.exit_code == 0, qPrintable(wide.err));
    QVERIFY2(wide.err.contains("map-80x20.exr: the depth map is 80x20 but the photo is 600x400 "
                               "(another aspect): depth is stretched per axis"),
             qPrintable(wide.err));
  }

  void refusesBadInputWithoutWriting() {
    const QByteArray before = hashOf(project_);
    const QString out = dir_.filePath("never.png");
    struct Case {
      QStringList args;
      int exit;
      QString says;
    };
    const QString missing = dir_.filePath("missing.artcamproj");
    const QString broken = dir_.filePath("broken.artcamproj");
    {
      QFile f(broken);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write(R"({"format":"artcam-studio-project","version":3,"photo":"coffee.png",)"
              R"("effects":[{"effect":"depth-of-field","params":{"focus":[-1]}}]})");
    }
    const QString no_photo = dir_.filePath("nophoto.artcamproj");
    {
      QFile f(no_photo);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write(R"({"format":"artcam-studio-project","version":1,"photo":"gone.png"})");
    }
    const Case cases[] = {
        {{"export", project_}, 2, "missing -o OUT"},
        {{"export", project_, "-o", out, "--quality", "0"}, 2, "--quality expects a whole number from 1 to 100"},
        {{"export", project_, "-o", out, "--bit-depth", "12"}, 2, "--bit-depth expects 8, 16, half or float"},
        {{"export", project_, "-o", out, "--crop-valid", "--fill", "0,0,0"}, 2, "exclude each other"},
        {{"export", project_, "-o", out, "--fill", "1,2"}, 2, "--fill expects 3 or 4"},
        {{"export", missing, "-o", out}, 1, "missing.artcamproj: cannot read"},
        {{"export", broken, "-o", out}, 1, "broken.artcamproj: /effects/0/params/focus: focus = -1 is outside its range"},
        {{"export", no_photo, "-o", out}, 1, "nophoto.artcamproj: its photo"},
        {{"export", no_photo, "-o", out, "--depth-out", out}, 2, "two outputs name the same file"},
        {{"export", project_, "-o", dir_.filePath("coffee.png"), "--overwrite"}, 1, "refusing to overwrite the input"},
        {{"export", project_, "-o", project_, "--overwrite"}, 1, "refusing to overwrite the input"},
    };
    for (const Case& c : cases) {
      const Run r = artcamCli(c.args);
      const QString what = c.args.join(' ') + " -> " + r.err;
      QVERIFY2(r.exit_code == c.exit, qPrintable(what));
      QVERIFY2(r.err.contains(c.says), qPrintable(what));
      QVERIFY2(r.err.trimmed().count('\n') <= 2, qPrintable(what));
      QVERIFY2(!QFile::exists(out), qPrintable(what));
    }
    QCOMPARE(hashOf(project_), before);
    QVERIFY(!hashOf(dir_.filePath("coffee.png")).isEmpty());
  }

  // The photo moved: --photo FILE renders FILE in its place, the same pixels as before the
  // move; a photo of another size than the project's masks is refused naming both sizes.
  void photoOptionStandsInForAMovedPhoto() {
    const QString before = dir_.filePath("before-move.png");
    const Run first = artcamCli({"export", project_, "-o", before, "-q"});
    QVERIFY2(first.exit_code == 0, qPrintable(first.err));
    QVERIFY(QDir().mkpath(dir_.filePath("moved/elsewhere")));
    const QString project = dir_.filePath("moved/depth-effects.artcamproj");
    const QString photo = dir_.filePath("moved/elsewhere/coffee.png");
    QVERIFY(QFile::copy(project_, project));
    QVERIFY(QFile::copy(dir_.filePath("coffee.png"), photo));
    const QString out = dir_.filePath("moved/after.png");
    const Run lost = artcamCli({"export", project, "-o", out, "-q"});
    QCOMPARE(lost.exit_code, 1);
    QVERIFY2(lost.err.contains("depth-effects.artcamproj: its photo") &&
                 lost.err.contains("--photo FILE") && lost.err.trimmed().count('\n') == 0,
             qPrintable(lost.err));
    const Run found = artcamCli({"export", project, "--photo", photo, "-o", out, "-q"});
    QVERIFY2(found.exit_code == 0, qPrintable(found.err));
    const auto a = readImage(before.toStdString()), b = readImage(out.toStdString());
    QVERIFY(a.ok() && b.ok());
    QVERIFY(a->image.data == b->image.data);
    // Another size: the masks were painted on a 600x400 photo.
    const QString small = dir_.filePath("moved/small.png");
    QVERIFY(writeImage(small.toStdString(), ImageF(60, 40, 3, -1)).ok);
    const QString never = dir_.filePath("moved/never.png");
    const Run wrong = artcamCli({"export", project, "--photo", small, "-o", never, "-q"});
    QCOMPARE(wrong.exit_code, 1);
    QVERIFY2(wrong.err.contains("depth-effects.artcamproj") && wrong.err.contains("small.png") &&
                 wrong.err.contains("60x40") && wrong.err.contains("600x400") &&
                 wrong.err.trimmed().count('\n') == 0,
             qPrintable(wrong.err));
    QVERIFY(!QFile::exists(never));
    const Run absent =
        artcamCli({"export", project, "--photo", dir_.filePath("nowhere.png"), "-o", never, "-q"});
    QCOMPARE(absent.exit_code, 1);
    QVERIFY2(absent.err.contains("depth-effects.artcamproj: --photo") &&
                 absent.err.contains("nowhere.png"),
             qPrintable(absent.err));
  }

  void cropAndFillChangeTheOutput() {
    // A project whose camera is a barrel lens (set by hand): its corners have no preimage.
    const QString lens = dir_.filePath("lens.artcamproj");
    const Run preset = artcamCli({"preset", "barrel", "--k", "-0.3", "--size", "600x400", "-o",
                                  dir_.filePath("barrel.artcam")});
    QVERIFY2(preset.exit_code == 0, qPrintable(preset.err));
    QFile cam(dir_.filePath("barrel.artcam"));
    QVERIFY(cam.open(QIODevice::ReadOnly));
    QFile f(lens);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(R"({"format":"artcam-studio-project","version":1,"photo":"coffee.png","camera":)" +
            cam.readAll() + "}");
    f.close();
    const Run crop = artcamCli({"export", lens, "-o", dir_.filePath("crop.png"), "--json", "-q", "--crop-valid"});
    QVERIFY2(crop.exit_code == 0, qPrintable(crop.err));
    const QJsonObject j = QJsonDocument::fromJson(crop.out.toUtf8()).object();
    QVERIFY2(j["width"].toInt() < 600 && j["height"].toInt() < 400, qPrintable(crop.out));
    const Run fill = artcamCli({"export", lens, "-o", dir_.filePath("fill.png"), "-q", "--fill", "1,0,0"});
    QVERIFY2(fill.exit_code == 0, qPrintable(fill.err));
    const auto filled = readImage(dir_.filePath("fill.png").toStdString());
    QVERIFY(filled.ok());
    QCOMPARE(filled->image.channels, 3);  // opaque after the fill
    const float* corner = filled->image.pixel(0, 0);
    QVERIFY2(corner[0] > 0.99f && corner[1] < 0.01f, "the corner is not the fill colour");
  }

 private:
  QTemporaryDir dir_;
  QString project_;

  // --size with one side 0: the other by the output's aspect (600x400 here, 3:2), as --help
  // says; both 0 or a bad side refused.
  void oneSideZeroIsByAspect() {
    for (const auto& [size, width, height] :
         {std::tuple<QString, int, int>{"300x0", 300, 200}, {"0x200", 300, 200}}) {
      const Run r = artcamCli({"export", project_, "-o", dir_.filePath("aspect.png"), "--size",
                               size, "--json", "-q", "--overwrite"});
      QVERIFY2(r.exit_code == 0, qPrintable(size + ": " + r.err));
      const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
      QCOMPARE(j["width"].toInt(), width);
      QCOMPARE(j["height"].toInt(), height);
    }
    for (const char* bad : {"0x0", "0xabc", "-3x0"}) {
      const Run r = artcamCli({"export", project_, "-o", dir_.filePath("bad.png"), "--size", bad});
      QCOMPARE(r.exit_code, 2);
      QVERIFY2(r.err.contains("--size"), qPrintable(r.err));
    }
  }
};

QTEST_GUILESS_MAIN(TestCliExport)
#include "test_cli_export.moc"
