// SPDX-License-Identifier: Apache-2.0
// A piecewise fit keeps its error bound BETWEEN its matches (issue 44, item 9): an 8 mm
// stereographic fisheye (lensfun's model, the independent truth) sampled on a grid of the source
// frame, fitted as `artcam fit --piecewise --max-error 1` fits a matches file, then compared with
// lensfun on a grid four times denser, offset from the fit's, so no point of it is a match. Both
// directions: the photo as shot → the rectilinear picture (lensfun's reverse modifier: for a
// distorted pixel, where the clean picture has it), and back (the correcting modifier). The
// camera is then checked as the CLI writes it (validateArtcam), so a patch whose image misses
// the target frame does not make the file unwritable.
#include "core/fit/fit_image.h"
#include "core/lens/lens_database.h"
#include "core/model/artcam.h"
#include "core/piecewise/piecewise_fit.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <lensfun/lensfun.h>

#include <cmath>
#include <cstdio>
#include <optional>

using namespace artcam;

namespace {

const char* const kFisheye = "Samyang 8mm f/3.5 Fish-Eye CS";  // stereographic

// lensfun's modifier at 8 mm with artcam's pixel centres (lensfun's integers are centres).
// `reverse`: the distorting modifier, which for a pixel of the distorted picture gives the point
// of the clean one; otherwise the correcting one, the other way round.
class Lensfun {
 public:
  Lensfun(const lfLens* lens, FrameSize size, bool reverse)
      : modifier_(lens, lens->CropFactor, size.width, size.height), size_(size) {
    modifier_.Initialize(lens, LF_PF_F32, 8.0f, 8.0f, 1000.0f, 1.0f, LF_RECTILINEAR,
                         LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY, reverse);
  }
  // Where `p` goes; empty where lensfun has no finite answer (beyond the half sphere) or sends
  // it further than ten frames away (as core/lens/lens_camera.cpp drops such samples).
  std::optional<Eigen::Vector2d> operator()(const Eigen::Vector2d& p) const {
    float r[2];
    if (!modifier_.ApplyGeometryDistortion(static_cast<float>(p.x() - 0.5),
                                           static_cast<float>(p.y() - 0.5), 1, 1, r))
      return std::nullopt;
    const Eigen::Vector2d q(r[0] + 0.5, r[1] + 0.5);
    const double far = 10.0 * std::max(size_.width, size_.height);
    if (!q.allFinite() || std::abs(q.x()) > far || std::abs(q.y()) > far) return std::nullopt;
    return q;
  }

 private:
  lfModifier modifier_;
  FrameSize size_;
};

// Matches on a grid of the source frame: source the grid point, target where lensfun sends it.
std::vector<PointMatch> gridMatches(const Lensfun& truth, FrameSize size, double step) {
  std::vector<PointMatch> out;
  for (double y = 0.5 * step; y < size.height; y += step)
    for (double x = 0.5 * step; x < size.width; x += step)
      if (const auto t = truth({x, y})) {
        PointMatch m;
        m.source = Eigen::Vector2d(x, y);
        m.target = *t;
        out.push_back(m);
      }
  return out;
}

struct HeldOut {
  double max_px = 0.0;
  int points = 0;
  int unanswered = 0;  // points inside a patch the camera does not map
};

// Every point of a grid `step / 4` apart, offset by `step / 8` from the fit's grid, that lies in
// one of the patches and has an answer from lensfun.
HeldOut heldOut(const PiecewiseCamera& camera, const Lensfun& truth, FrameSize size, double step) {
  HeldOut h;
  const double d = step / 4;
  for (double y = d / 2; y < size.height; y += d)
    for (double x = d / 2; x < size.width; x += d) {
      const Eigen::Vector2d p(x, y);
      const auto t = truth(p);
      if (!t || camera.patchAt(p) < 0) continue;
      ++h.points;
      const auto got = camera.targetPixelFromSourcePixel(p);
      if (!got) {
        ++h.unanswered;
        continue;
      }
      h.max_px = std::max(h.max_px, (*got - *t).norm());
    }
  return h;
}

}  // namespace

class TestLensPiecewiseFit : public QObject {
  Q_OBJECT
  std::shared_ptr<const LensDatabase> db_;

  void fitBothWays(FrameSize size, double step) {
    const auto entry = db_->find(kFisheye, 0.0);
    QVERIFY2(entry.ok(), entry.status.message.c_str());
    const lfLens* lens = db_->lens(entry->index);
    for (const bool to_rectilinear : {true, false}) {
      const Lensfun truth(lens, size, /*reverse=*/to_rectilinear);
      const std::vector<PointMatch> matches = gridMatches(truth, size, step);
      PiecewiseOptions options;
      options.max_error_px = 1.0;
      const PiecewiseSummary fit = fitPiecewise(matches, size, size, options);
      QVERIFY2(fit.status.ok, fit.status.message.c_str());
      const HeldOut h = heldOut(fit.camera, truth, size, step);
      std::printf("%s %dx%d, step %g: %zu matches, %s\n  held out: max %.3g px over %d points, "
                  "%d unanswered\n",
                  to_rectilinear ? "fisheye → rectilinear" : "rectilinear → fisheye", size.width,
                  size.height, step, matches.size(), fit.report().c_str(), h.max_px, h.points,
                  h.unanswered);
      QVERIFY(h.points > 30000);
      QCOMPARE(h.unanswered, 0);
      QVERIFY2(h.max_px <= 1.5 * options.max_error_px, qPrintable(QString::number(h.max_px)));
      
      // At the matches within the bound, and the held-out figure it reports near the truth's.
      QVERIFY2(fit.max_px <= options.max_error_px, fit.report().c_str());
      QVERIFY2(fit.held_out_max_px <= 1.5 * options.max_error_px, fit.report().c_str());

      // Written as `artcam fit --piecewise` writes it: the single camera on top, the patches
      // beside it; a valid camera, whatever part of the target frame a patch misses.
      FitOptions single_options;
      single_options.diagnostics = false;
      const FitSummary single = fitImageCamera(matches, size, size, single_options);
      Artcam doc(single.status ? single.camera : fit.camera.patches.front().camera);
      doc.pieces = fit.camera;
      const Status valid = validateArtcam(doc);
      QVERIFY2(valid.ok, valid.message.c_str());
    }
  }

 private slots:
  void initTestCase() {
    auto db = LensDatabase::load();
    QVERIFY2(db.ok(), db.status.message.c_str());
    db_ = *db.value;
  }

  // 1920×1080 with a match every 32 px: about 2000 matches, 16–55 patches.
  void fisheyeHoldsItsBoundBetweenMatches() { fitBothWays({1920, 1080}, 32.0); }
};

QTEST_APPLESS_MAIN(TestLensPiecewiseFit)
#include "test_lens_piecewise_fit.moc"
