// SPDX-License-Identifier: Apache-2.0
// artcam export-map and fit --stmap, checked against truths that do not come from the map
// writer: the camera's forward map (every stored source position must land on its pixel
// centre), the closed-form inverse of a homography, artcam warp's own alpha, OpenImageIO's
// ImageBufAlgo::st_warp (Nuke's STMap semantics) against artcam warp of the same photo, and a
// camera fitted back from the map against the camera the map was made from. Files are read with
// OpenImageIO directly, and the photo is written with it, so the project's image code is not
// its own witness.
#include "core/io/artcam_file.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "tests/app/cli_run.h"
#include "tests/support/test_support.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <Eigen/LU>

#include <QtTest/QtTest>

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <cmath>

using namespace artcam;
using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

constexpr int kW = 600, kH = 400;

struct MapFile {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::string format;      // "float", "half", …
  std::string convention;  // the artcam:convention attribute
  int source_width = 0, source_height = 0;
  std::vector<float> values;
  float at(int i, int j, int c) const {
    return values[(static_cast<size_t>(j) * static_cast<size_t>(width) + static_cast<size_t>(i)) *
                      channels.size() +
                  static_cast<size_t>(c)];
  }
};

MapFile readMap(const QString& path) {
  MapFile m;
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return m;
  const OIIO::ImageSpec& spec = in->spec();
  m.width = spec.width;
  m.height = spec.height;
  m.channels = spec.channelnames;
  m.format = spec.format.c_str();
  m.convention = spec.get_string_attribute("artcam:convention");
  m.source_width = spec.get_int_attribute("artcam:source_width");
  m.source_height = spec.get_int_attribute("artcam:source_height");
  m.values.resize(static_cast<size_t>(m.width) * static_cast<size_t>(m.height) * m.channels.size());
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, m.values.data())) return {};
  return m;
}

// source_from_target in pixels with a horizon inside the output: w = 0.004 x + 0.0005 y - 0.4
// vanishes on the line x = 100 - y / 8, and the output pixels left of it have no preimage (the
// points they would read lie beyond the camera's pole line, on the far side of infinity).
Eigen::Matrix3d sourceFromTarget() {
  Eigen::Matrix3d g;
  g << 1.0, 0.02, 0.0,  //
      0.01, 1.0, 0.0,   //
      0.004, 0.0005, -0.4;
  return g;
}
Eigen::Matrix3d perspectiveHomography() { return sourceFromTarget().inverse(); }

Camera cameraFromPixelHomography(const Eigen::Matrix3d& h_px, FrameSize size) {
  const Eigen::Matrix3d h_n =
      normalizedFromPixelMatrix(size) * h_px * pixelFromNormalizedMatrix(size);
  Stage stage;
  for (const Eigen::MatrixXd& q : liftHomography(h_n)) stage.q.push_back(q);
  return Camera({Block{BlockKind::Position, 3}}, {stage}, size, size);
}

// Smooth ramps plus noise, linear float: every pixel differs, so a half-pixel slip shows.
bool writePhoto(const QString& path) {
  OIIO::ImageSpec spec(kW, kH, 3, OIIO::TypeDesc::FLOAT);
  std::vector<float> pixels(static_cast<size_t>(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        pixels[(static_cast<size_t>(y) * kW + static_cast<size_t>(x)) * 3 +
               static_cast<size_t>(c)] =
            static_cast<float>(0.6 * (x + c * y) / (kW + kH) + test::uniform(0.0, 0.4));
  auto out = OIIO::ImageOutput::create(path.toStdString());
  return out && out->open(path.toStdString(), spec) &&
         out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
}

QStringList lines(const QString& text) { return text.split('\n', Qt::SkipEmptyParts); }

}  // namespace

class TestCliExportMap : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    Run r = artcamCli({"preset", "barrel", "--k", "-0.15", "-o", path("barrel.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"preset", "pincushion", "--k", "0.15", "-o", path("pincushion.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Camera persp = cameraFromPixelHomography(perspectiveHomography(), {kW, kH});
    QCOMPARE(analyseStructure(persp).geometry, GeometryClass::Homography);
    QVERIFY(writeArtcam(path("persp.artcam").toStdString(), Artcam(persp)).ok);
    QVERIFY(writePhoto(path("photo.exr")));
  }

  // Every stored source position, pushed through the camera's forward map, lands on its own
  // output pixel centre; R = G = 0 exactly where alpha is 0.
  void storedPositionsLandOnPixelCentres() {
    for (const char* name : {"barrel", "persp"}) {
      const QString map_path = path(QString(name) + "-st.exr");
      const Run r = artcamCli({"export-map", path(QString(name) + ".artcam"), "--size", "600x400",
                               "-o", map_path, "--json"});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      const MapFile map = readMap(map_path);
      QCOMPARE(map.width, kW);
      QCOMPARE(map.height, kH);
      QCOMPARE(map.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
      QCOMPARE(map.format, std::string("float"));
      QCOMPARE(map.convention, std::string("stmap"));
      QCOMPARE(map.source_width, kW);
      QCOMPARE(map.source_height, kH);
      const auto camera = readArtcam(path(QString(name) + ".artcam").toStdString());
      QVERIFY(camera.ok());
      double worst = 0.0;
      long long valid = 0, invalid = 0;
      for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
          const float a = map.at(i, j, 3);
          QVERIFY(a == 0.0f || a == 1.0f);
          QCOMPARE(map.at(i, j, 2), 0.0f);
          if (a == 0.0f) {
            QCOMPARE(map.at(i, j, 0), 0.0f);
            QCOMPARE(map.at(i, j, 1), 0.0f);
            ++invalid;
            continue;
          }
          ++valid;
          const Eigen::Vector2d source(map.at(i, j, 0) * double(kW),
                                       (1.0 - map.at(i, j, 1)) * double(kH));
          const auto target = targetPixelFromSourcePixel(camera->main(), source);
          QVERIFY(target.has_value());
          worst = std::max(worst, (*target - Eigen::Vector2d(i + 0.5, j + 0.5)).norm());
        }
      qInfo("%s: %lld pixels with a preimage, %lld without, worst landing %.3g px", name, valid,
            invalid, worst);
      QVERIFY2(worst < 1e-3, name);
      const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
      QCOMPARE(j["invalid_pixels"].toInteger(), invalid);
      if (QString(name) == "persp") {
        QCOMPARE(j["kernel"].toString(), QString("homography"));
        QVERIFY2(invalid > 1000,
                 "the perspective test camera must leave pixels without a preimage");
      } else {
        QCOMPARE(j["kernel"].toString(), QString("rational"));
      }
    }
  }

  // The map's alpha is 0 exactly where the pixel has no preimage: artcam warp leaves those
  // transparent, and every other transparent pixel of the warp reads from outside the photo.
  void alphaMatchesTheWarpsTransparency() {
    const QString map_path = path("persp-alpha.exr"), warped = path("persp-warped.exr");
    Run r = artcamCli({"export-map", path("persp.artcam"), "--size", "600x400", "-o", map_path});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", path("photo.exr"), path("persp.artcam"), "-o", warped, "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const MapFile map = readMap(map_path);
    const MapFile warp = readMap(warped);
    QCOMPARE(warp.width, kW);
    QCOMPARE(warp.channels.size(), size_t{4});
    long long no_preimage = 0, outside = 0, inside = 0;
    for (int j = 0; j < kH; ++j)
      for (int i = 0; i < kW; ++i) {
        const float warp_alpha = warp.at(i, j, 3);
        if (map.at(i, j, 3) == 0.0f) {
          QCOMPARE(warp_alpha, 0.0f);
          ++no_preimage;
          continue;
        }
        // Bilinear taps reach half a pixel past the photo's edge, fading to 0 there.
        const double x = map.at(i, j, 0) * double(kW), y = (1.0 - map.at(i, j, 1)) * double(kH);
        const double margin = 1e-2;
        const bool far_out = x < -0.5 - margin || y < -0.5 - margin || x > kW + 0.5 + margin ||
                             y > kH + 0.5 + margin;
        const bool well_in = x > -0.5 + margin && y > -0.5 + margin && x < kW + 0.5 - margin &&
                             y < kH + 0.5 - margin;
        if (far_out) {
          QCOMPARE(warp_alpha, 0.0f);
          ++outside;
        } else if (well_in) {
          QVERIFY2(warp_alpha > 0.0f, qPrintable(QString("pixel %1,%2").arg(i).arg(j)));
          ++inside;
        }
      }
    qInfo("no preimage %lld, reads outside the photo %lld, inside %lld", no_preimage, outside,
          inside);
    QVERIFY(no_preimage > 1000);
    QVERIFY(inside > kW * kH / 8);
  }

  // Nuke's STMap semantics, as OpenImageIO implements them (st_warp with flip_t): warping the
  // photo with the exported map gives what artcam warp gives.
  void stWarpAgreesWithArtcamWarp() {
    // Pincushion magnifies everywhere, so st_warp's triangle filter of width 2 stays bilinear.
    const QString map_path = path("pin-st.exr"), warped = path("pin-warped.exr");
    Run r =
        artcamCli({"export-map", path("pincushion.artcam"), "--size", "600x400", "-o", map_path});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", path("photo.exr"), path("pincushion.artcam"), "-o", warped, "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const OIIO::ImageBuf photo(path("photo.exr").toStdString());
    const OIIO::ImageBuf st(map_path.toStdString());
    const MapFile ours = readMap(warped);
    QCOMPARE(ours.width, kW);
    const auto meanDifference = [&](bool flip_t) {
      const OIIO::ImageBuf theirs =
          OIIO::ImageBufAlgo::st_warp(photo, st, "triangle", 2.0f, 0, 1, false, flip_t);
      if (theirs.has_error() || theirs.spec().width != kW) return 1e9;
      double sum = 0.0;
      float pel[3];
      for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
          theirs.getpixel(i, j, pel, 3);
          for (int c = 0; c < 3; ++c) sum += std::abs(double(pel[c]) - ours.at(i, j, c));
        }
      return sum / (3.0 * kW * kH);
    };
    const double right = meanDifference(true);
    qInfo("st_warp vs artcam warp: mean |difference| %.3g (%.3g / 255)", right, right * 255.0);
    QVERIFY(right < 0.5 / 255.0);
    // The comparison can fail: read with t counting down (the convention mixed up), it does.
    const double flipped = meanDifference(false);
    qInfo("control, t not flipped: mean |difference| %.3g", flipped);
    QVERIFY(flipped > 10.0 / 255.0);
  }

  // cv::remap's convention: map_x = x - 0.5, map_y = y - 0.5 of the closed-form inverse of the
  // homography, -1 where there is no preimage; the same pixels as the STMap's alpha 0.
  void opencvConventionIsOffsetByHalfAPixel() {
    const QString cv_path = path("persp-cv.exr"), st_path = path("persp-st2.exr");
    Run r = artcamCli({"export-map", path("persp.artcam"), "--size", "600x400", "-o", cv_path,
                       "--convention", "opencv"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"export-map", path("persp.artcam"), "--size", "600x400", "-o", st_path});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const MapFile cv = readMap(cv_path), st = readMap(st_path);
    QCOMPARE(cv.channels, (std::vector<std::string>{"R", "G"}));
    QCOMPARE(cv.format, std::string("float"));
    QCOMPARE(cv.convention, std::string("opencv"));
    const Eigen::Matrix3d inverse = sourceFromTarget();
    double worst = 0.0;
    long long none = 0;
    for (int j = 0; j < kH; ++j)
      for (int i = 0; i < kW; ++i) {
        if (st.at(i, j, 3) == 0.0f) {
          QCOMPARE(cv.at(i, j, 0), -1.0f);
          QCOMPARE(cv.at(i, j, 1), -1.0f);
          ++none;
          continue;
        }
        const Eigen::Vector3d s = inverse * Eigen::Vector3d(i + 0.5, j + 0.5, 1.0);
        QVERIFY(s.z() > 0.0);  // in front of the camera: a preimage
        // Near the horizon sources run to 1e5 px, where a float's spacing alone is 0.008 px:
        // the error is taken relative to the size of the coordinate there.
        const double x = s.x() / s.z(), y = s.y() / s.z();
        const double scale = 1.0 + std::max(std::abs(x), std::abs(y)) / 1000.0;
        worst = std::max({worst, std::abs(cv.at(i, j, 0) - (x - 0.5)) / scale,
                          std::abs(cv.at(i, j, 1) - (y - 0.5)) / scale});
      }
    qInfo(
        "opencv map vs the closed-form inverse: worst %.3g px (per 1000 px of coordinate beyond "
        "the first), %lld pixels without",
        worst, none);
    QVERIFY(worst < 1e-3);
    QVERIFY(none > 1000);
    // And the pixels the closed form puts behind the camera are exactly the -1 ones.
    for (int j = 0; j < kH; j += 7)
      for (int i = 0; i < kW; i += 7) {
        const Eigen::Vector3d s = inverse * Eigen::Vector3d(i + 0.5, j + 0.5, 1.0);
        if (s.z() < -1e-9) QCOMPARE(cv.at(i, j, 0), -1.0f);
      }
  }

  // Round trip: the barrel's map fitted back gives the barrel, within 0.05 px; also at another
  // map size (the source size then comes from the header), and piecewise.
  void fitStmapRecoversTheCamera() {
    const auto original = readArtcam(path("barrel.artcam").toStdString());
    QVERIFY(original.ok());
    struct Case {
      QString size;
      double scale;  // target pixels of the map per target pixel of the camera
    };
    for (const Case& c : {Case{"600x400", 1.0}, Case{"300x200", 0.5}}) {
      const QString map_path = path("barrel-" + c.size + ".exr");
      const QString fitted_path = path("barrel-fitted-" + c.size + ".artcam");
      Run r = artcamCli({"export-map", path("barrel.artcam"), "--size", c.size, "-o", map_path});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      r = artcamCli({"fit", "--stmap", map_path, "-o", fitted_path, "--json", "-q"});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
      QCOMPARE(j["model"].toString(), QString("quadratic"));
      QVERIFY(j["matches"].toInt() > 1000 && j["matches"].toInt() <= 4000);
      QVERIFY(j["max_px"].toDouble() < 0.05);
      const auto fitted = readArtcam(fitted_path.toStdString());
      QVERIFY2(fitted.ok(), fitted.status.message.c_str());
      QCOMPARE(fitted->main().sourceSize().width, kW);
      QCOMPARE(fitted->main().targetSize().width, int(kW * c.scale));
      double worst = 0.0;
      for (int y = 0; y <= kH; y += 10)
        for (int x = 0; x <= kW; x += 10) {
          const auto a = targetPixelFromSourcePixel(original->main(), Eigen::Vector2d(x, y));
          const auto b = targetPixelFromSourcePixel(fitted->main(), Eigen::Vector2d(x, y));
          QVERIFY(a && b);
          worst = std::max(worst, (*a * c.scale - *b).norm() / c.scale);
        }
      qInfo("fit --stmap at %s: worst %.3g px from the original barrel", qPrintable(c.size), worst);
      QVERIFY(worst < 0.05);
    }
    const QString pieces_path = path("barrel-pieces.artcam");
    const Run r = artcamCli({"fit", "--stmap", path("barrel-600x400.exr"), "--piecewise", "-o",
                             pieces_path, "--json", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const auto pieces = readArtcam(pieces_path.toStdString());
    QVERIFY2(pieces.ok() && pieces->pieces, pieces.status.message.c_str());
    double worst = 0.0;
    for (int y = 20; y <= kH - 20; y += 10)
      for (int x = 20; x <= kW - 20; x += 10) {
        const auto a = targetPixelFromSourcePixel(original->main(), Eigen::Vector2d(x, y));
        const auto b = pieces->pieces->targetPixelFromSourcePixel(Eigen::Vector2d(x, y));
        QVERIFY(a && b);
        worst = std::max(worst, (*a - *b).norm());
      }
    qInfo("fit --stmap --piecewise: worst %.3g px", worst);
    QVERIFY(worst < 0.05);
  }

  // A map made elsewhere: RGB without alpha and without artcam's header, as Nuke writes one,
  // filled here from the formula R = x / W, G = 1 - y / H of a known homography (source twice the
  // map's size, given with --size). The fitted camera must be that homography. The overscan row
  // has a data window 8 px larger than the display window on every side, as Nuke writes maps
  // with a bounding box: targets are display-window pixels.
  void fitsAForeignMapWithoutAlpha_data() {
    QTest::addColumn<int>("overscan");
    QTest::newRow("display window") << 0;
    QTest::newRow("overscan") << 8;
  }
  void fitsAForeignMapWithoutAlpha() {
    QFETCH(int, overscan);
    constexpr int mw = 320, mh = 240, sw = 640, sh = 480;
    Eigen::Matrix3d source_from_target;
    source_from_target << 1.9, 0.1, 20.0,  //
        -0.05, 2.05, 8.0,                  //
        1.0e-4, -2.0e-4, 1.0;
    const QString map_path = path(QString("foreign-%1.exr").arg(overscan));
    {
      const int dw = mw + 2 * overscan, dh = mh + 2 * overscan;
      OIIO::ImageSpec spec(dw, dh, 3, OIIO::TypeDesc::FLOAT);
      spec.x = spec.y = -overscan;
      spec.full_x = spec.full_y = 0;
      spec.full_width = mw;
      spec.full_height = mh;
      std::vector<float> pixels(static_cast<size_t>(dw) * static_cast<size_t>(dh) * 3);
      for (int j = 0; j < dh; ++j)
        for (int i = 0; i < dw; ++i) {
          const Eigen::Vector3d s =
              source_from_target * Eigen::Vector3d(i - overscan + 0.5, j - overscan + 0.5, 1.0);
          float* p =
              &pixels[(static_cast<size_t>(j) * static_cast<size_t>(dw) + static_cast<size_t>(i)) *
                      3];
          p[0] = static_cast<float>(s.x() / s.z() / sw);
          p[1] = static_cast<float>(1.0 - s.y() / s.z() / sh);
          p[2] = 0.0f;
        }
      auto out = OIIO::ImageOutput::create(map_path.toStdString());
      QVERIFY(out && out->open(map_path.toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    const QString fitted_path = path(QString("foreign-%1.artcam").arg(overscan));
    const Run r = artcamCli({"fit", "--stmap", map_path, "--size", "640x480", "--model",
                             "homography", "-o", fitted_path, "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("640x480"), qPrintable(r.out));
    const auto fitted = readArtcam(fitted_path.toStdString());
    QVERIFY(fitted.ok());
    QCOMPARE(fitted->main().sourceSize().width, sw);
    QCOMPARE(fitted->main().targetSize().width, mw);
    double worst = 0.0;
    for (int j = 0; j < mh; j += 8)
      for (int i = 0; i < mw; i += 8) {
        const Eigen::Vector3d s = source_from_target * Eigen::Vector3d(i + 0.5, j + 0.5, 1.0);
        const auto t = targetPixelFromSourcePixel(fitted->main(),
                                                  Eigen::Vector2d(s.x() / s.z(), s.y() / s.z()));
        QVERIFY(t.has_value());
        worst = std::max(worst, (*t - Eigen::Vector2d(i + 0.5, j + 0.5)).norm());
      }
    qInfo("foreign map: the fitted homography lands within %.3g px", worst);
    QVERIFY(worst < 1e-3);
  }

  // The fit must be able to fail the round trip: a map of another camera does not give the
  // barrel back (the comparison above is not vacuous).
  void roundTripComparisonCanFail() {
    const QString map_path = path("pin-for-fit.exr"), fitted_path = path("pin-fitted.artcam");
    Run r =
        artcamCli({"export-map", path("pincushion.artcam"), "--size", "600x400", "-o", map_path});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"fit", "--stmap", map_path, "-o", fitted_path, "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const auto barrel = readArtcam(path("barrel.artcam").toStdString());
    const auto fitted = readArtcam(fitted_path.toStdString());
    QVERIFY(barrel.ok() && fitted.ok());
    const auto a = targetPixelFromSourcePixel(barrel->main(), Eigen::Vector2d(20, 20));
    const auto b = targetPixelFromSourcePixel(fitted->main(), Eigen::Vector2d(20, 20));
    QVERIFY(a && b);
    QVERIFY((*a - *b).norm() > 1.0);
  }

  void refusesBadInputsInOneLine() {
    // A map without R and G: a one-channel EXR made here.
    const QString luma = path("luma.exr");
    {
      OIIO::ImageSpec spec(32, 32, 1, OIIO::TypeDesc::FLOAT);
      spec.channelnames = {"Y"};
      std::vector<float> pixels(32 * 32, 0.5f);
      auto out = OIIO::ImageOutput::create(luma.toStdString());
      QVERIFY(out && out->open(luma.toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    Run r = artcamCli({"fit", "--stmap", luma, "-o", path("never1.artcam")});
    QCOMPARE(r.exit_code, 1);
    QCOMPARE(lines(r.err).size(), 1);
    QVERIFY2(r.err.contains(luma) && r.err.contains("R and G"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("never1.artcam")));

    // A map whose alpha is 0 everywhere: nothing to fit.
    const QString empty = path("empty.exr");
    {
      OIIO::ImageSpec spec(32, 32, 4, OIIO::TypeDesc::FLOAT);
      spec.channelnames = {"R", "G", "B", "A"};
      spec.alpha_channel = 3;
      std::vector<float> pixels(32 * 32 * 4, 0.0f);
      auto out = OIIO::ImageOutput::create(empty.toStdString());
      QVERIFY(out && out->open(empty.toStdString(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    }
    r = artcamCli({"fit", "--stmap", empty, "-o", path("never2.artcam")});
    QCOMPARE(r.exit_code, 1);
    QCOMPARE(lines(r.err).size(), 1);
    QVERIFY2(r.err.contains(empty), qPrintable(r.err));

    // --size missing: a usage error naming it (plus the dispatcher's "see --help" line).
    r = artcamCli({"export-map", path("barrel.artcam"), "-o", path("never.exr")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(lines(r.err).first().contains("--size"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("never.exr")));

    // An unknown convention, a layered camera, a map that is not EXR, an existing output.
    r = artcamCli({"export-map", path("barrel.artcam"), "--size", "60x40", "-o", path("never.exr"),
                   "--convention", "maya"});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(lines(r.err).first().contains("--convention"), qPrintable(r.err));
    r = artcamCli({"preset", "chromatic-aberration", "-o", path("ca.artcam")});
    QCOMPARE(r.exit_code, 0);
    r = artcamCli({"export-map", path("ca.artcam"), "--size", "60x40", "-o", path("never.exr")});
    QCOMPARE(r.exit_code, 1);
    QCOMPARE(lines(r.err).size(), 1);
    QVERIFY2(r.err.contains("ca.artcam") && r.err.contains("layer"), qPrintable(r.err));
    r = artcamCli({"export-map", path("barrel.artcam"), "--size", "60x40", "-o", path("map.png")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("OpenEXR"), qPrintable(r.err));
    QVERIFY(!QFile::exists(path("map.png")));
    QVERIFY(!QFile::exists(path("never.exr")));
    r = artcamCli(
        {"export-map", path("barrel.artcam"), "--size", "60x40", "-o", path("photo.exr")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("--overwrite"), qPrintable(r.err));

    // fit --stmap takes no MATCHES.csv, and its map is never its output.
    r = artcamCli({"fit", "--stmap", path("barrel-st.exr"), "extra.csv", "-o", path("n.artcam")});
    QCOMPARE(r.exit_code, 2);
    r = artcamCli(
        {"fit", "--stmap", path("barrel-st.exr"), "-o", path("barrel-st.exr"), "--overwrite"});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("input"), qPrintable(r.err));
  }

 private:
  QString path(const QString& name) const { return dir_.filePath(name); }
  QTemporaryDir dir_;
};

QTEST_GUILESS_MAIN(TestCliExportMap)
#include "test_cli_export_map.moc"
