// SPDX-License-Identifier: Apache-2.0
// Vignetting in the lens camera against lensfun itself (issue 49): the camera's render of a
// picture against lensfun's own pipeline on the same picture — lfModifier::
// ApplyColorModification over the whole frame, then its geometry (ApplyGeometryDistortion) read
// bilinearly — for correcting and for simulating (lensfun's reverse modifier: geometry first,
// then the colour). And the flat-field fit against gains made outside the model: the cos⁴ law of
// natural vignetting about a shifted axis, and lensfun's own simulated vignetting.
#include "core/io/artcam_file.h"
#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/lens/vignetting.h"
#include "core/pipeline/render.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <lensfun/lensfun.h>

#include <QTemporaryDir>

#include <algorithm>
#include <cmath>

using namespace artcam;

namespace {

const char* const kPrime = "Canon EF 50mm f/1.8 MkII";  // ptlens + pa vignetting per aperture
constexpr double kCrop = 1.6;  // an APS-C body: one camera meets 0.5 px at this crop
const FrameSize kSize{600, 400};

// A smooth picture (so resampling filters agree to well under the tolerance), linear RGB.
float picture(double x, double y, int c) {
  return static_cast<float>(0.45 + 0.2 * std::sin(x / 47.0 + c) * std::cos(y / 61.0 - c));
}
ImageF makePicture(FrameSize size) {
  ImageF out(size.width, size.height, 3);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      for (int c = 0; c < 3; ++c) out.pixel(x, y)[c] = picture(x + 0.5, y + 0.5, c);
  return out;
}

// Bilinear read at artcam pixel point (x, y) of an RGB image (clamped at the outer centres).
double bilinear(const ImageF& im, double x, double y, int c) {
  const double fx = std::clamp(x - 0.5, 0.0, im.width - 1.0),
               fy = std::clamp(y - 0.5, 0.0, im.height - 1.0);
  const int x0 = std::min(static_cast<int>(fx), im.width - 2),
            y0 = std::min(static_cast<int>(fy), im.height - 2);
  const double tx = fx - x0, ty = fy - y0;
  const auto at = [&](int i, int j) { return double(im.pixel(x0 + i, y0 + j)[c]); };
  return (1 - ty) * ((1 - tx) * at(0, 0) + tx * at(1, 0)) +
         ty * ((1 - tx) * at(0, 1) + tx * at(1, 1));
}

struct Lensfun {
  lfModifier geometry, colour;
  Lensfun(const lfLens* lens, FrameSize size, float aperture, bool reverse)
      : geometry(lens, float(kCrop), size.width, size.height),
        colour(lens, float(kCrop), size.width, size.height) {
    geometry.Initialize(lens, LF_PF_F32, 50.0f, aperture, 1000.0f, 1.0f, LF_RECTILINEAR,
                        LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY, reverse);
    colour.Initialize(lens, LF_PF_F32, 50.0f, aperture, 1000.0f, 1.0f, LF_RECTILINEAR,
                      LF_MODIFY_VIGNETTING, reverse);
  }
  // Where target pixel point t reads the source (artcam pixel points).
  Eigen::Vector2d source(const Eigen::Vector2d& t) const {
    float r[2];
    geometry.ApplyGeometryDistortion(float(t.x() - 0.5), float(t.y() - 0.5), 1, 1, r);
    return {r[0] + 0.5, r[1] + 0.5};
  }
  // lensfun's colour step over a whole RGB float image, in place, row by row.
  void applyColour(ImageF& im) const {
    for (int y = 0; y < im.height; ++y)
      colour.ApplyColorModification(im.pixel(0, y), 0.0f, float(y), im.width, 1,
                                    LF_CR_3(RED, GREEN, BLUE), im.width * 3 * int(sizeof(float)));
  }
};

// The camera's render of `in` (RGB) against lensfun's: the largest relative difference over the
// target pixels whose source lies 2 px inside the frame, and the largest gain lensfun applied
// there (so a camera without vignetting cannot pass).
struct Compared {
  double max_relative = 0.0;
  double max_gain = 1.0, min_gain = 1.0;
  int pixels = 0;
};
Compared compare(const Artcam& camera, const ImageF& in, const Lensfun& truth, bool reverse) {
  ImageF colour_first = in;
  if (!reverse) truth.applyColour(colour_first);
  ImageF expected(in.width, in.height, 3);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const Eigen::Vector2d s = truth.source({x + 0.5, y + 0.5});
      for (int c = 0; c < 3; ++c)
        expected.pixel(x, y)[c] = float(bilinear(colour_first, s.x(), s.y(), c));
    }
  if (reverse) truth.applyColour(expected);
  const ImageF out = render(RenderInputs::of(in), camera);
  Compared m;
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const Eigen::Vector2d s = truth.source({x + 0.5, y + 0.5});
      if (s.x() < 2 || s.y() < 2 || s.x() > in.width - 2 || s.y() > in.height - 2) continue;
      // lensfun's gain at this pixel: its picture over the unvignetted one.
      const double plain = bilinear(in, s.x(), s.y(), 1);
      const double gain = expected.pixel(x, y)[1] / plain;
      m.max_gain = std::max(m.max_gain, gain);
      m.min_gain = std::min(m.min_gain, gain);
      const float* o = out.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        const double e = o[c] / o[3] / expected.pixel(x, y)[c] - 1.0;
        m.max_relative = std::max(m.max_relative, std::abs(e));
      }
      ++m.pixels;
    }
  return m;
}

}  // namespace

class TestLensVignetting : public QObject {
  Q_OBJECT
  std::shared_ptr<const LensDatabase> db_;

  LensCameraOptions options(double aperture, bool distort, bool tca) const {
    LensCameraOptions o;
    o.lens = kPrime;
    o.focal_mm = 50;
    o.crop = kCrop;
    o.size = kSize;
    o.aperture = aperture;
    o.distort = distort;
    o.tca = tca;
    return o;
  }
  const lfLens* lens() const { return db_->lens(db_->find(kPrime, kCrop)->index); }

 private slots:
  void initTestCase() {
    auto db = LensDatabase::load();
    QVERIFY2(db.ok(), db.status.message.c_str());
    db_ = *db.value;
  }

  // Correcting at f/2 (a strong fall-off) and f/8,
  // with and without TCA layers: the camera's picture is lensfun's within 0.5 % everywhere.
  void correctAgainstLfModifier() {
    const ImageF in = makePicture(kSize);
    for (double aperture : {2.0, 8.0})
      for (bool tca : {false, true}) {
        const LensCameraSummary s = lensCamera(*db_, options(aperture, false, tca));
        QVERIFY2(s.status.ok, s.status.message.c_str());
        QVERIFY(!s.piecewise);
        QVERIFY(s.vignetting);
        QCOMPARE(s.tca, tca);
        QVERIFY(validateArtcam(s.camera).ok);
        QVERIFY2(s.vignetting_fit.max_percent < 0.5, s.report().c_str());
        const Compared m =
            compare(s.camera, in, Lensfun(lens(), kSize, float(aperture), false), false);
        const QString what = QString("f/%1 tca %2: max %3 %, gain up to %4 over %5 px")
                                 .arg(aperture)
                                 .arg(tca)
                                 .arg(100 * m.max_relative)
                                 .arg(m.max_gain)
                                 .arg(m.pixels);
        QVERIFY2(m.pixels > 200000, qPrintable(what));
        // There is vignetting to correct (lensfun's gain inside the frame: 1.39 at f/2, 1.07 at
        // f/8).
        QVERIFY2(m.max_gain > (aperture < 4 ? 1.3 : 1.05), qPrintable(what));
        QVERIFY2(m.max_relative < 0.005, qPrintable(what));
      }
  }

  // Simulating (--distort): lensfun's reverse modifier warps the clean picture and then darkens
  // it at the target; the camera does both in one.
  void simulateAgainstReverseModifier() {
    const ImageF in = makePicture(kSize);
    const LensCameraSummary s = lensCamera(*db_, options(2.0, true, false));
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY(s.vignetting);
    const Compared m = compare(s.camera, in, Lensfun(lens(), kSize, 2.0f, true), true);
    const QString what =
        QString("max %1 %, gain down to %2").arg(100 * m.max_relative).arg(m.min_gain);
    QVERIFY2(m.min_gain < 0.75, qPrintable(what));
    QVERIFY2(m.max_relative < 0.005, qPrintable(what));
  }

  // Without an aperture there is no vignetting to fit: a note says what to give; --no-vignetting
  // leaves it out silently; the vignetting camera writes and reads back as the same camera.
  void apertureAndFile() {
    const LensCameraSummary none = lensCamera(*db_, options(0.0, false, false));
    QVERIFY(none.status.ok);
    QVERIFY(!none.vignetting);
    QVERIFY(!hasShading(none.camera.main()));
    QVERIFY(std::any_of(none.notes.begin(), none.notes.end(), [](const std::string& n) {
      return n.find("give the aperture") != std::string::npos;
    }));
    LensCameraOptions off = options(2.0, false, false);
    off.vignetting = false;
    QVERIFY(!hasShading(lensCamera(*db_, off).camera.main()));
    QVERIFY(!lensCamera(*db_, options(-1.0, false, false)).status.ok);

    const LensCameraSummary s = lensCamera(*db_, options(2.0, false, true));
    QTemporaryDir dir;
    const std::string path = dir.filePath("v.artcam").toStdString();
    QVERIFY(writeArtcam(path, s.camera).ok);
    const Result<Artcam> back = readArtcam(path);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->layers.size(), size_t{3});
    const ImageF in = makePicture(kSize);
    const ImageF a = render(RenderInputs::of(in), s.camera),
                 b = render(RenderInputs::of(in), *back);
    double worst = 0.0;
    for (size_t i = 0; i < a.data.size(); ++i)
      worst = std::max(worst, double(std::abs(a.data[i] - b.data[i])));
    QVERIFY2(worst < 1e-5, qPrintable(QString::number(worst)));
  }

  // A flat field darkened by the cos⁴ law about an axis 40 px right and 25 px up of the frame's
  // centre, with 0.5 % noise: the fitted camera's gain is 1/cos⁴ within 1 % over the frame, its
  // centre found within 3 px, and the corrected field flat.
  void flatFieldCosFourth() {
    const FrameSize size{900, 600};
    const Eigen::Vector2d axis(490.0, 275.0);
    const double f = 0.9 * 0.5 * std::hypot(900.0, 600.0);
    const auto cos4 = [&](const Eigen::Vector2d& p) {
      const double c = f / std::hypot(f, (p - axis).norm());
      return c * c * c * c;
    };
    ImageF flat(size.width, size.height, 3);
    std::normal_distribution<double> noise(0.0, 0.005);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        for (int c = 0; c < 3; ++c)
          flat.pixel(x, y)[c] = float(0.7 * cos4({x + 0.5, y + 0.5}) * (1.0 + noise(test::rng())));
    const FlatFieldSummary s = fitFlatField(flat);
    QVERIFY2(s.fit.status.ok, s.fit.status.message.c_str());
    QVERIFY2(
        (s.fit.gain.centre_px - axis).norm() < 3.0,
        qPrintable(
            QString("centre %1, %2").arg(s.fit.gain.centre_px.x()).arg(s.fit.gain.centre_px.y())));
    double worst = 0.0;
    for (int y = 0; y <= 600; y += 20)
      for (int x = 0; x <= 900; x += 20) {
        const Eigen::Vector2d p(x, y);
        worst = std::max(worst, std::abs(s.fit.gain(p) * cos4(p) - 1.0));
      }
    QVERIFY2(worst < 0.01, qPrintable(QString::number(worst)));
    QVERIFY(s.darkest < 0.6);
    // The corrected field is flat: every 30 px cell within 1 % of the centre's level.
    const ImageF out = render(RenderInputs::of(flat), Artcam(s.camera));
    const float* centre = out.pixel(490, 275);
    for (int y = 15; y < 600; y += 30)
      for (int x = 15; x < 900; x += 30) {
        double sum = 0;
        for (int j = -7; j <= 7; ++j)
          for (int i = -7; i <= 7; ++i) sum += out.pixel(x + i, y + j)[1];
        QVERIFY2(std::abs(sum / 225.0 / centre[1] - 1.0) < 0.01,
                 qPrintable(QString("%1,%2").arg(x).arg(y)));
      }
  }

  // A flat field shot through lensfun's lens (its reverse colour modifier on grey): the fitted
  // correction is lensfun's own correction within 0.75 % over the frame (f/2: lensfun's gain
  // reaches 1.9; its cubic's inverse is what a ratio of quadratics in r² follows to 0.4–0.5 %).
  void flatFieldFromLensfun() {
    ImageF flat(kSize.width, kSize.height, 3);
    std::fill(flat.data.begin(), flat.data.end(), 0.6f);
    Lensfun(lens(), kSize, 2.0f, true).applyColour(flat);
    const FlatFieldSummary s = fitFlatField(flat);
    QVERIFY2(s.fit.status.ok, s.fit.status.message.c_str());
    const Lensfun correct(lens(), kSize, 2.0f, false);
    double worst = 0.0;
    for (int y = 0; y < kSize.height; y += 10)
      for (int x = 0; x < kSize.width; x += 10) {
        alignas(16) float rgb[3] = {1, 1, 1};
        correct.colour.ApplyColorModification(rgb, float(x), float(y), 1, 1,
                                              LF_CR_3(RED, GREEN, BLUE), 12);
        worst = std::max(worst, std::abs(s.fit.gain({x + 0.5, y + 0.5}) / rgb[1] - 1.0));
      }
    const QString what = QString("%1 % against lensfun, the fit's own figure %2 %")
                             .arg(100 * worst)
                             .arg(s.fit.max_percent);
    QVERIFY2(worst < 0.0075, qPrintable(what));
  }

  // A flat field with a black region has no gain that flattens it: refused, naming where.
  void flatFieldRefusals() {
    ImageF flat(300, 200, 3);
    std::fill(flat.data.begin(), flat.data.end(), 0.5f);
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) std::fill(flat.pixel(x, y), flat.pixel(x, y) + 3, 0.0f);
    const FlatFieldSummary s = fitFlatField(flat);
    QVERIFY(!s.fit.status.ok);
    QVERIFY2(s.fit.status.message.find("(0, 0)") != std::string::npos,
             s.fit.status.message.c_str());
    QVERIFY(!fitFlatField(ImageF(3, 2, 3)).fit.status.ok);
  }
};

QTEST_APPLESS_MAIN(TestLensVignetting)
#include "test_lens_vignetting.moc"
