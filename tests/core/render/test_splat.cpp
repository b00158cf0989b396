// SPDX-License-Identifier: Apache-2.0
// The forward splat (splat.h) where it used to break: pinholes where triangles of both size
// classes meet on a textured photo (also after a homography), and hard edges that the camera
// pulls apart (a colour step under the eq 8/9 colour shift, a depth step under crossed slits).
// Expected coverage and colours come from the maps written here in closed form: the colour
// shift y = p·(1 + s·r) (chromatic.h) and the homography's own inverse.
#include "core/effects/chromatic.h"
#include "core/effects/effect_table.h"
#include "core/model/artcam.h"
#include "core/model/compose.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/pipeline/render.h"
#include "core/render/attributed.h"
#include "core/render/splat.h"
#include "tests/core/render/photo_fixture.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <Eigen/LU>

#include <cmath>

using namespace artcam;

namespace {

// The paper's own ARTcam effect at the settings: red expands, blue shrinks (eq 8/9).
constexpr std::array<double, 3> kShift = {0.15, 0.0, -0.1};

// Output pixels whose every preimage lies at least `margin` px inside the source: for each layer
// k the colour shift's preimage of t (normalised) is t/(1 + s_k·r) for some r in [0, 1], so the
// homography's preimages of the segment from t to t/(1 + s_k) must lie inside (the source
// rectangle is convex and a homography keeps segments, so the ends decide).
std::vector<bool> interiorMask(FrameSize size, const Eigen::Matrix3d& target_from_source,
                               double margin) {
  const Eigen::Matrix3d source_from_target = target_from_source.inverse();
  std::vector<bool> mask(static_cast<size_t>(size.width) * static_cast<size_t>(size.height));
  const auto inside = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector3d h = source_from_target * Eigen::Vector3d(q.x(), q.y(), 1.0);
    if (!(h.z() > 0)) return false;
    const Eigen::Vector2d s = pixelFromNormalized(size, h.head<2>() / h.z());
    return s.x() > margin && s.y() > margin && s.x() < size.width - margin &&
           s.y() < size.height - margin;
  };
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const Eigen::Vector2d t = normalizedFromPixel(size, {x + 0.5, y + 0.5});
      bool ok = inside(t);
      for (double s : kShift) ok = ok && inside(t / (1.0 + s));
      mask[static_cast<size_t>(y) * static_cast<size_t>(size.width) + static_cast<size_t>(x)] = ok;
    }
  return mask;
}

struct Coverage {
  long long interior = 0, partly = 0;  // interior pixels, and those with 0 ≤ alpha < 1
};

Coverage coverageOf(const ImageF& out, const std::vector<bool>& mask) {
  Coverage c;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      if (!mask[static_cast<size_t>(y) * static_cast<size_t>(out.width) + static_cast<size_t>(x)])
        continue;
      ++c.interior;
      c.partly += out.pixel(x, y)[3] < 1.0f - 1e-5f;
    }
  return c;
}

Artcam colourShift(FrameSize size) {
  Artcam cs;
  cs.layers = colourShiftLayers({kShift}, size, size);
  return cs;
}

// The longest run of neighbouring pixels along row y whose channel c lies strictly between the
// two sides of a step (more than 2 % from both).
int longestRamp(const ImageF& img, int y, int c, float low, float high) {
  int longest = 0, run = 0;
  for (int x = 0; x < img.width; ++x) {
    const float v = img.pixel(x, y)[c];
    const float margin = 0.02f * (high - low);
    run = (v > low + margin && v < high - margin) ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

}  // namespace

class TestSplat : public QObject {
  Q_OBJECT

 private slots:
  // coffee.png under the colour shift: every interior pixel covered fully (alpha 1).
  void colourShiftOfAPhotoHasNoPinholes() {
    const ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const FrameSize size{photo.width, photo.height};
    RenderSummary summary;
    const ImageF out = render(RenderInputs::of(photo), colourShift(size), {}, &summary);
    QCOMPARE(summary.path, RenderPath::Layered);
    const Coverage c = coverageOf(out, interiorMask(size, Eigen::Matrix3d::Identity(), 2.0));
    qInfo("colour shift of coffee.png: %lld of %lld interior pixels partly transparent", c.partly,
          c.interior);
    QVERIFY(c.interior > size.width * size.height / 2);
    QCOMPARE(c.partly, 0LL);
  }

  // The same camera after a homography (compose h cs: a tilt that minifies one side and
  // magnifies the other, so triangles of both size classes meet everywhere).
  void colourShiftAfterAHomographyHasNoPinholes() {
    const ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    const FrameSize size{photo.width, photo.height};
    Eigen::Matrix3d h;  // target_from_source, normalised frames, column form
    h << 0.9, 0.12, 0.02, -0.08, 0.95, 0.01, 0.25, -0.15, 1.0;
    Stage st;
    for (const Eigen::MatrixXd& q : liftHomography(h)) st.q.push_back(q);
    const Artcam homography(Camera({Block{BlockKind::Position, 3}}, {st}, size, size));
    const Result<Artcam> composed = composeArtcams(homography, colourShift(size));
    QVERIFY2(composed.ok(), composed.ok() ? "" : composed.status.message.c_str());
    RenderSummary summary;
    const ImageF out = render(RenderInputs::of(photo), *composed, {}, &summary);
    const Coverage c = coverageOf(out, interiorMask(size, h, 2.0));
    qInfo("homography then colour shift of coffee.png: %lld of %lld interior pixels partly "
          "transparent", c.partly, c.interior);
    QVERIFY(c.interior > size.width * size.height / 4);
    QCOMPARE(c.partly, 0LL);
  }

  // s = 0 everywhere: the geometry still reads colour (the splat path), but every pixel centre
  // lands on itself, so the picture is the source exactly, at an odd and an even S, every pixel
  // (the border included) opaque.
  void theNeutralShiftReturnsTheSourceExactly() {
    const FrameSize size{53, 41};
    ImageF src(size.width, size.height, 3);
    for (float& v : src.data) v = static_cast<float>(test::uniform(0.0, 1.0));
    Artcam cs;
    cs.layers = colourShiftLayers({{0.0, 0.0, 0.0}}, size, size);
    for (int s : {3, 4}) {
      RenderOptions o;
      o.splat_supersample = s;
      RenderSummary summary;
      const ImageF out = render(RenderInputs::of(src), cs, o, &summary);
      QCOMPARE(summary.path, RenderPath::Layered);
      double worst = 0.0;
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, static_cast<double>(std::abs(out.pixel(x, y)[c] - src.pixel(x, y)[c])));
          worst = std::max(worst, 1.0 - out.pixel(x, y)[3]);
        }
      QVERIFY2(worst < 1e-6, qPrintable(QString("S = %1: off by %2").arg(s).arg(worst)));
    }
  }

  // A hard-edged red square under colour-shift s_red = 0.12: the red layer moves each red pixel
  // to 1.12·p, black ones stay. Where t/1.12 lies in the square the output is red (the expanded
  // square covers the black it moves over: no darkened band where the mesh folds); where
  // neither t nor t/1.12 does it is black; in between (the gap the square leaves behind) it is
  // red or black, never a ramp: no run of intermediate pixels longer than 1.
  void aShiftedSquareKeepsItsHardEdges() {
    const FrameSize size{240, 160};
    const int x0 = 150, x1 = 210, y0 = 90, y1 = 140;  // off-centre, so every edge moves
    ImageF src(size.width, size.height, 3);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) src.pixel(x, y)[0] = 1.0f;
    const double s = 0.12;
    Artcam cs;
    cs.layers = colourShiftLayers({{s, 0.0, 0.0}}, size, size);
    const ImageF out = render(RenderInputs::of(src), cs);
    const auto inSquare = [&](const Eigen::Vector2d& n, double margin) {
      const Eigen::Vector2d p = pixelFromNormalized(size, n);
      return p.x() > x0 + margin && p.x() < x1 - margin && p.y() > y0 + margin && p.y() < y1 - margin;
    };
    const auto outsideSquare = [&](const Eigen::Vector2d& n, double margin) {
      const Eigen::Vector2d p = pixelFromNormalized(size, n);
      return p.x() < x0 - margin || p.x() > x1 + margin || p.y() < y0 - margin || p.y() > y1 + margin;
    };
    int red = 0, black = 0, worst_ramp = 0;
    double worst_red = 0.0, worst_black = 0.0, worst_alpha = 0.0;
    for (int y = 8; y < size.height - 8; ++y) {
      for (int x = 8; x < size.width - 8; ++x) {
        const float* p = out.pixel(x, y);
        worst_alpha = std::max(worst_alpha, 1.0 - p[3]);
        const Eigen::Vector2d t = normalizedFromPixel(size, {x + 0.5, y + 0.5});
        if (inSquare(t / (1.0 + s), 1.0)) {
          worst_red = std::max(worst_red, 1.0 - p[0]);
          ++red;
        } else if (outsideSquare(t / (1.0 + s), 1.0) && outsideSquare(t, 1.0)) {
          worst_black = std::max(worst_black, static_cast<double>(p[0]));
          ++black;
        }
      }
      worst_ramp = std::max(worst_ramp, longestRamp(out, y, 0, 0.0f, 1.0f));
    }
    qInfo("shifted square: red short by %.3f, black over by %.3f, longest ramp %d px, alpha "
          "short by %.3g", worst_red, worst_black, worst_ramp, worst_alpha);
    QVERIFY(red > 3000 && black > 10000);
    QVERIFY2(worst_ramp <= 1, qPrintable(QString("a %1 px ramp").arg(worst_ramp)));
    QVERIFY2(worst_red < 0.02, qPrintable(QString("red darkened by %1").arg(worst_red)));
    QVERIFY2(worst_black < 0.02, qPrintable(QString("black reddened by %1").arg(worst_black)));
    QVERIFY2(worst_alpha < 1e-5, qPrintable(QString("alpha short by %1").arg(worst_alpha)));
  }

  // Crossed slits over a painted depth step (a near box at depth 1 on a far wall at 3, with
  // their own colours): the near box moves against the wall and lies in front of it where they
  // overlap, neither smears into the other (no intermediate colour run longer than 1 px along any
  // row), and the gap it uncovers shows the wall, every pixel covered.
  void aDepthStepDoesNotStreak() {
    const FrameSize size{160, 120};
    ImageF photo(size.width, size.height, 3);
    ImageF depth(size.width, size.height, 1);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x) {
        const bool near = x >= 90 && x < 130 && y >= 20 && y < 100;
        photo.pixel(x, y)[0] = near ? 0.9f : 0.1f;
        photo.pixel(x, y)[1] = 0.5f;
        photo.pixel(x, y)[2] = near ? 0.1f : 0.9f;
        depth.pixel(x, y)[0] = near ? 1.0f : 3.0f;
      }
    EffectValues values;
    values["slit-u-behind"] = {2.0};
    values["slit-v-behind"] = {0.0};
    values["reference-depth"] = {3.0};
    const Artcam xslit = buildEffect("photo-xslit", values, size);
    RenderSummary summary;
    const ImageF out = render(RenderInputs::of(photo, &depth), xslit, {}, &summary);
    QCOMPARE(summary.path, RenderPath::Splat);
    // The wall (d = 3 = d_r) stays; the box (d = 1) maps u' = k·u, k = d(d_r + s_u)/(d_r(d + s_u))
    // = 5/9, so it narrows towards the centre: it covers the wall on its left, and on its right
    // it uncovers wall the photo never saw, which must show the wall, not the box stretched.
    const double k = 5.0 / 9.0;
    int worst_ramp = 0, box = 0, wall = 0;
    double worst_alpha = 0.0, worst_colour = 0.0;
    for (int y = 24; y < 96; ++y) {
      worst_ramp = std::max(worst_ramp, longestRamp(out, y, 0, 0.1f, 0.9f));
      for (int x = 10; x < size.width - 10; ++x) {
        worst_alpha = std::max(worst_alpha, 1.0 - out.pixel(x, y)[3]);
        const Eigen::Vector2d t = normalizedFromPixel(size, {x + 0.5, y + 0.5});
        const double sx = pixelFromNormalized(size, {t.x() / k, t.y()}).x();  // a box point's source
        const bool in_box = sx > 91 && sx < 129, off_box = sx < 89 || sx > 131;
        if (in_box) ++box;
        if (off_box) ++wall;
        if (in_box || off_box)
          worst_colour = std::max(worst_colour, std::abs(out.pixel(x, y)[0] - (in_box ? 0.9 : 0.1)));
      }
    }
    qInfo("crossed slits over a depth step: longest ramp %d px, colour off by %.3f, alpha short by "
          "%.3g", worst_ramp, worst_colour, worst_alpha);
    QVERIFY(box > 1000 && wall > 5000);
    QVERIFY2(worst_ramp <= 1, qPrintable(QString("a %1 px ramp").arg(worst_ramp)));
    QVERIFY2(worst_colour < 0.01, qPrintable(QString("colour off by %1").arg(worst_colour)));
    QVERIFY2(worst_alpha < 1e-5, qPrintable(QString("alpha short by %1").arg(worst_alpha)));
  }
};

QTEST_GUILESS_MAIN(TestSplat)
#include "test_splat.moc"
