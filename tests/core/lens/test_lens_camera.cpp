// SPDX-License-Identifier: Apache-2.0
// Cameras from the lensfun database against lfModifier itself, the independent truth: for
// points of the frame off the fit's and the check's grids (random, seeded), lensfun's modifier
// says where each target pixel reads the source, and the camera must send that source point
// back to the target pixel within the threshold. The pixel convention is lensfun's documented
// one (integer coordinates are pixel centres; artcam's are at i + 0.5), and is checked on its
// own by a closed form: a centred radial lens keeps the frame centre fixed.
// Real database lenses: a ptlens compact zoom (piecewise), a ptlens zoom with strong TCA
// (single camera, three layers), a ptlens prime calibrated on three crops, a stereographic fisheye converted to rectilinear, and --distort.
#include "core/effects/chromatic.h"
#include "core/io/artcam_file.h"
#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/model/frames.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <algorithm>

#include <lensfun/lensfun.h>

#include <cmath>
#include <optional>

using namespace artcam;

namespace {

const char* const kCompact = "Canon PowerShot G11 & compatibles (Standard)";  // ptlens
const char* const kPrime = "Canon EF 50mm f/1.8 MkII";                        // ptlens, 3 crops
const char* const kTcaZoom = "Lumix G Vario 45-200mm f/4.0-5.6 Mega OIS";      // ptlens + poly3 TCA
const char* const kFisheye = "Samyang 8mm f/3.5 Fish-Eye CS";                 // stereographic

// lensfun's answer for artcam target pixel `t`, channel 0..2 (red, green, blue).
struct Truth {
  lfModifier modifier;
  bool tca;
  Truth(const lfLens* lens, float crop, FrameSize size, float focal, bool reverse, bool with_tca)
      : modifier(lens, crop, size.width, size.height), tca(with_tca) {
    int flags = LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY | (with_tca ? LF_MODIFY_TCA : 0);
    modifier.Initialize(lens, LF_PF_F32, focal, 8.0f, 1000.0f, 1.0f, LF_RECTILINEAR, flags,
                        reverse);
  }
  Eigen::Vector2d source(const Eigen::Vector2d& t, int channel) {
    float r[6];
    const float x = static_cast<float>(t.x() - 0.5), y = static_cast<float>(t.y() - 0.5);
    if (tca) {
      modifier.ApplySubpixelGeometryDistortion(x, y, 1, 1, r);
      return {r[2 * channel] + 0.5, r[2 * channel + 1] + 0.5};
    }
    modifier.ApplyGeometryDistortion(x, y, 1, 1, r);
    return {r[0] + 0.5, r[1] + 0.5};
  }
};

// Where the camera (layer `layer`, or the patches) sends a source pixel.
std::optional<Eigen::Vector2d> mapped(const Artcam& cam, const Eigen::Vector2d& source_px,
                                      int layer = 0) {
  if (cam.pieces) return cam.pieces->targetPixelFromSourcePixel(source_px);
  const Camera& c = cam.layers.at(static_cast<size_t>(layer));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(c.dimension());
  x.head<2>() = normalizedFromPixel(c.sourceSize(), source_px);
  const Eigen::VectorXd y = c.evaluate(x);
  if (!y.head<2>().allFinite()) return std::nullopt;
  return pixelFromNormalized(c.targetSize(), y.head<2>());
}

struct Measured {
  double max_px = 0.0;
  int points = 0;
};

// Random target pixels (not on any grid) whose lensfun source lies in the frame.
Measured measure(const Artcam& cam, Truth& truth, FrameSize size, int channel = 1,
                 int layer = 0) {
  Measured m;
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector2d t(test::uniform(0.5, size.width - 0.5),
                            test::uniform(0.5, size.height - 0.5));
    const Eigen::Vector2d s = truth.source(t, channel);
    if (s.x() < 0 || s.y() < 0 || s.x() > size.width || s.y() > size.height) continue;
    const auto got = mapped(cam, s, layer);
    m.max_px = std::max(m.max_px, got ? (*got - t).norm() : 1e9);
    ++m.points;
  }
  return m;
}

// The options every case starts from: a lens of the database, its focal length, the photo size.
LensCameraOptions optionsFor(const char* lens_name, double focal_mm, FrameSize size) {
  LensCameraOptions o;
  o.lens = lens_name;
  o.focal_mm = focal_mm;
  o.size = size;
  return o;
}

}  // namespace

class TestLensCamera : public QObject {
  Q_OBJECT
  std::shared_ptr<const LensDatabase> db_;

  const lfLens* lens(const char* name, double crop = 0.0) {
    const auto e = db_->find(name, crop);
    if (!e) qFatal("%s", e.status.message.c_str());
    return db_->lens(e->index);
  }

 private slots:
  void initTestCase() {
    auto db = LensDatabase::load();
    QVERIFY2(db.ok(), db.status.message.c_str());
    db_ = *db.value;
    QVERIFY(db_->size() > 500);  // Debian 12's database holds over a thousand lenses
  }

  // A ptlens compact zoom at its wide end needs patches at this size; the piecewise camera
  // meets lensfun within the threshold between the grids too, and the summary's own figure is
  // what an independent measurement finds.
  void compactZoomAgainstLfModifier() {
    const FrameSize size{1200, 800};
    LensCameraOptions o = optionsFor(kCompact, 6.1, size);
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY(s.piecewise);
    QVERIFY(s.single_max_px > 0.5);  // why it is piecewise
    QVERIFY(s.within_tolerance);
    QVERIFY(s.max_px <= 0.5);
    QVERIFY(validateArtcam(s.camera).ok);
    Truth truth(lens(kCompact), static_cast<float>(s.crop), size, 6.1f, false, false);
    const Measured m = measure(s.camera, truth, size);
    QVERIFY(m.points > 3000);
    QVERIFY2(m.max_px <= 0.55, qPrintable(QString::number(m.max_px)));
    QVERIFY(std::abs(m.max_px - s.max_px) < 0.15);
    QCOMPARE(s.crop, double(lens(kCompact)->CropFactor));  // --crop defaults to the calibration's
  }

  // The closed form for the convention: a radial lens centred on the frame (CenterX = CenterY
  // = 0) leaves the frame centre (w/2, h/2 in artcam pixels) where it is. A half-pixel slip
  // between lensfun's pixels and artcam's on one side of the map would move it by about 0.7 px
  // (a uniform slip on both sides only shows where the magnification is far from 1, which the
  // comparisons above would not see at their threshold).
  void frameCentreStaysPut() {
    const FrameSize size{600, 400};
    LensCameraOptions o = optionsFor(kPrime, 50, size);
    o.crop = 1.0;
    o.tca = false;
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QCOMPARE(lens(kPrime, 1.0)->CenterX, 0.0f);
    const auto c = mapped(s.camera, {300.0, 200.0});
    QVERIFY(c);
    QVERIFY2((*c - Eigen::Vector2d(300.0, 200.0)).norm() < 0.02,
             qPrintable(QString("%1 %2").arg(c->x()).arg(c->y())));
  }

  // TCA: a single camera of three layers, each meeting lensfun's own subpixel coordinates of
  // its channel; red and blue really differ from green (the database's poly3 TCA at the
  // corners), so the layers are not three copies.
  void tcaLayersAgainstLfModifier() {
    const FrameSize size{1600, 1200};
    LensCameraOptions o = optionsFor(kTcaZoom, 45, size);
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY(!s.piecewise);
    QVERIFY(s.tca);
    QCOMPARE(s.camera.layers.size(), size_t{3});
    QVERIFY(validateArtcam(s.camera).ok);
    Truth truth(lens(kTcaZoom), static_cast<float>(s.crop), size, 45.0f, false, true);
    for (int channel = 0; channel < 3; ++channel) {
      const Measured m = measure(s.camera, truth, size, channel, channel);
      QVERIFY2(m.max_px <= 0.55, qPrintable(QString::number(m.max_px)));
    }
    // The channels' sources at a corner differ by lensfun's TCA; the layers carry it.
    const Eigen::Vector2d corner(0.5, 0.5);
    const double tca_px = (truth.source(corner, 0) - truth.source(corner, 2)).norm();
    const auto red = mapped(s.camera, truth.source(corner, 0), 0);
    const auto blue_of_red = mapped(s.camera, truth.source(corner, 0), 2);
    QVERIFY(red && blue_of_red);
    QVERIFY2(tca_px > 0.3, qPrintable(QString::number(tca_px)));  // 0.5 px in the database
    QVERIFY(std::abs((*red - *blue_of_red).norm() - tca_px) < 0.3);
  }

  // A stereographic fisheye converted to rectilinear: far from one quadratic, so patches.
  void fisheyeToRectilinear() {
    const FrameSize size{1500, 1000};
    LensCameraOptions o = optionsFor(kFisheye, 8, size);
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QCOMPARE(s.lens.type, std::string("fisheye (stereographic)"));
    QVERIFY(s.piecewise);
    QVERIFY(s.within_tolerance);
    QVERIFY(!s.notes.empty());  // the database's TCA is named as left out
    Truth truth(lens(kFisheye), static_cast<float>(s.crop), size, 8.0f, false, false);
    const Measured m = measure(s.camera, truth, size);
    QVERIFY(m.points > 3000);
    QVERIFY2(m.max_px <= 0.55, qPrintable(QString::number(m.max_px)));
  }

  // --distort is lensfun's reverse modifier.
  void distortAgainstReverseModifier() {
    const FrameSize size{1200, 800};
    LensCameraOptions o = optionsFor(kCompact, 6.1, size);
    o.distort = true;
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY(s.within_tolerance);
    Truth truth(lens(kCompact), static_cast<float>(s.crop), size, 6.1f, true, false);
    const Measured m = measure(s.camera, truth, size);
    QVERIFY2(m.max_px <= 0.55, qPrintable(QString::number(m.max_px)));
    // The two directions differ by pixels at the corner, so the check tells them apart.
    Truth forward(lens(kCompact), static_cast<float>(s.crop), size, 6.1f, false, false);
    QVERIFY((forward.source({0.5, 0.5}, 1) - truth.source({0.5, 0.5}, 1)).norm() > 2.0);
  }

  // A circular fisheye simulated at 600×400 cannot meet 0.5 px near its rim, where cells
  // split to the deepest level: over 1024 patches, more than a camera holds, used to reach the
  // writer and fail there. The tree stops a level higher instead: a camera that writes and
  // reads back, its error reported above the threshold, and a note that says why.
  void patchLimitStopsTheTreeNotTheWrite() {
    LensCameraOptions o = optionsFor("Sigma 8mm f/3.5 EX DG Circular", 8, {600, 400});
    o.crop = 1.0;
    o.distort = true;
    const LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY(s.piecewise);
    QVERIFY2(s.patches <= kMaxPatches && s.patches > 256, qPrintable(QString::number(s.patches)));
    QVERIFY(!s.within_tolerance);
    QVERIFY2(validateArtcam(s.camera).ok, validateArtcam(s.camera).message.c_str());
    const std::string notes = [&] {
      std::string all;
      for (const std::string& n : s.notes) all += n + "\n";
      return all;
    }();
    QVERIFY2(notes.find("the tree stops at depth 5") != std::string::npos, notes.c_str());
    QTemporaryDir dir;
    const std::string file = dir.filePath("fisheye.artcam").toStdString();
    QVERIFY(writeArtcam(file, s.camera).ok);
    const Result<Artcam> back = readArtcam(file);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(static_cast<int>(back->pieces->patches.size()), s.patches);
  }

  void refusals() {
    LensCameraOptions o = optionsFor(kCompact, 50, {600, 400});  // the G11 zooms 6.1-30.5 mm
    LensCameraSummary s = lensCamera(*db_, o);
    QVERIFY(!s.status.ok);
    QVERIFY(QString::fromStdString(s.status.message).contains("6.1-30.5"));
    o.lens = "Canon PowerShot G11";  // not a full name
    s = lensCamera(*db_, o);
    QVERIFY(!s.status.ok);
    QVERIFY(QString::fromStdString(s.status.message).contains(kCompact));  // suggested
  }

  void search() {
    const std::vector<LensEntry> hits = db_->search("canon 10-22");
    QVERIFY(!hits.empty());
    bool found = false;
    for (const LensEntry& e : hits) {
      const QString name = QString::fromStdString(e.maker + " " + e.model).toLower();
      QVERIFY(name.contains("canon") && name.contains("10-22"));
      found = found || e.model == "Canon EF-S 10-22mm f/3.5-4.5 USM";
    }
    QVERIFY(found);
    // Word beginnings: "8mm" is not "18mm".
    for (const LensEntry& e : db_->search("samyang 8mm"))
      QVERIFY2(!QString::fromStdString(e.model).contains("18mm"), e.model.c_str());
    // An exact name comes first.
    QCOMPARE(db_->search(kFisheye).front().model, std::string(kFisheye));
    QVERIFY(db_->search("").empty());
    QVERIFY(db_->search("nosuchlensmakerxyz").empty());
    // "1.4" begins no space-separated word of "Nikon AF-S Nikkor 50mm f/1.4G" (Debian's
    // slr-nikon.xml): lensfun's own matcher, which splits at punctuation, finds it.
    LensSearchMatch how = LensSearchMatch::None;
    const std::vector<LensEntry> nikon = db_->search("nikon 50mm 1.4", 0, &how);
    QCOMPARE(how, LensSearchMatch::Lensfun);
    QVERIFY(std::any_of(nikon.begin(), nikon.end(), [](const LensEntry& e) {
      return e.model == "Nikon AF-S Nikkor 50mm f/1.4G";
    }));
    for (const LensEntry& e : nikon)
      QVERIFY2(QString::fromStdString(e.model).contains("50mm"), e.model.c_str());
    // Only some words known: the loose match, still the lenses holding them.
    const std::vector<LensEntry> loose = db_->search("nikkor 50mm zzzunknownword", 0, &how);
    QCOMPARE(how, LensSearchMatch::LensfunLoose);
    QVERIFY(!loose.empty());
    // Of several calibrations, the crop nearest the one asked for.
    QCOMPARE(db_->find(kPrime, 1.6)->crop_factor, double(1.622f));
    QCOMPARE(db_->find(kPrime, 1.0)->crop_factor, 1.0);
  }

  // A photo's EXIF: the lens name finds the lens; without it, the camera's own (compact) lens.
  void suggest() {
    LensHint hint;
    hint.camera_maker = "Canon";
    hint.camera_model = "Canon PowerShot G11";
    hint.focal_mm = 6.1;
    const std::vector<LensEntry> from_camera = db_->suggest(hint);
    QVERIFY(!from_camera.empty());
    QCOMPARE(from_camera.front().model, std::string(kCompact));
    hint = {};
    hint.lens_model = "EF-S 10-22mm f/3.5-4.5 USM";
    hint.focal_mm = 10;
    const std::vector<LensEntry> from_lens = db_->suggest(hint);
    QVERIFY(!from_lens.empty());
    QCOMPARE(from_lens.front().model, std::string("Canon EF-S 10-22mm f/3.5-4.5 USM"));
    // A Nikon body's EXIF: lensfun knows the camera (its crop factor 1 is the camera's, in
    // slr-nikon.xml), and its lens by the name the camera writes.
    hint = {};
    hint.camera_maker = "NIKON CORPORATION";
    hint.camera_model = "NIKON D750";
    hint.lens_model = "AF-S Nikkor 50mm f/1.4G";
    hint.focal_mm = 50;
    const PhotoLensLookup nikon = db_->lookUp(hint);
    QVERIFY2(nikon.camera.find("D750") != std::string::npos, nikon.camera.c_str());
    QCOMPARE(nikon.camera_crop, 1.0);
    QVERIFY(!nikon.lenses.empty());
    QCOMPARE(nikon.lenses.front().model, std::string("Nikon AF-S Nikkor 50mm f/1.4G"));
  }
};

QTEST_APPLESS_MAIN(TestLensCamera)
#include "test_lens_camera.moc"
