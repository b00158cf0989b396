// SPDX-License-Identifier: Apache-2.0
// Depth effects across the soft fringe of a painted depth region, through the render front door
// (what `artcam warp`, `batch` and the studio's preview call) and through the project export
// (`artcam export PROJECT` and the studio's File ▸ Export: the project's depth layer rasterised,
// the effect stack assembled after the geometry, renderExport). The region is painted with the
// studio's brush (a soft stroke), its plane set by three points at depths 3 and 8.
//
// What must hold (docs/architecture.md, "Depth effects follow the painted coverage"): the
// amount of effect — blur or haze, measured as the mean change it makes to the photo in each
// column — fades with the mask's coverage: no step from the full effect to none within a pixel
// at the fringe's outer edge, no peak on the fringe above the effect inside the region (the
// plane stays within its points' depths there), never rising as the coverage falls, and the
// photo untouched where no coverage reaches.
#include "core/depth/depth_raster.h"
#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "core/effects/effect_table.h"
#include "core/pipeline/render.h"
#include "core/project/document_camera.h"
#include "core/project/project_render.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

constexpr int kW = 200, kH = 120;
constexpr int kInside = 55;   // a column fully covered on every row, at the far point's depth
constexpr int kOutside = 110; // from here on no coverage on any row

// Grey stripes across the rows, period 16 px: a blur across rows lowers their contrast by a
// factor that keeps falling with σ (≈ 0.5 at σ = 3 px, 0.17 at 4.8 px), so a larger blur shows
// as a larger change; the stripes run along the columns, so the column of a pixel says its
// coverage and nothing else.
ImageF stripes() {
  ImageF img(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int k = 0; k < 3; ++k)
        img.pixel(x, y)[k] = static_cast<float>(
            0.5 + 0.4 * std::sin(2.0 * M_PI * (y + 0.5) / 16.0) - 0.05 * k);
  return img;
}

// The studio's brush: one stroke down the left edge, radius 100, hardness 0.6 — opaque to
// x ≈ 60, a smoothstep fringe from there to x ≈ 100.
RegionMask brushedRegion() {
  RegionMask mask(kW, kH);
  const BrushOptions brush{100.0, 0.6, false};
  mask.stamp({0.0, -60.0}, brush);
  mask.segment({0.0, -60.0}, {0.0, kH + 60.0}, brush);
  return mask;
}

// Two points at depth 3 and one at 8, 10 px inside the opaque part's edge.
std::vector<DepthAnchor> anchors() {
  return {DepthAnchor{{10.0, 20.0}, 3.0}, DepthAnchor{{10.0, 100.0}, 3.0},
          DepthAnchor{{50.0, 60.0}, 8.0}};
}

EffectStep step(const QString& effect) {
  if (effect == "depth-of-field")  // focus at the near points: σ = 0.04·(1 − 3/z)·100 px
    return {"depth-of-field", {{"focus", {3.0}}, {"blur", {0.04}}, {"thin-lens", {1.0}}}};
  return {"aerial-perspective", {{"strength", {0.8}}, {"near", {1.0}}, {"far", {100.0}}}};
}

// The mean change the effect makes to the photo in column x, summed over the colour channels,
// away from the top and bottom rows (the blur's border).
double amountAt(const ImageF& out, const ImageF& photo, int x) {
  double sum = 0.0;
  int n = 0;
  for (int y = 16; y < kH - 16; ++y, ++n)
    for (int k = 0; k < 3; ++k)
      sum += std::abs(static_cast<double>(out.pixel(x, y)[k]) - photo.pixel(x, y)[k]);
  return sum / n;
}

}  // namespace

class TestDepthFringe : public QObject {
  Q_OBJECT

 private slots:
  void effectFadesWithTheFringe_data() {
    QTest::addColumn<QStringList>("effects");
    QTest::addColumn<bool>("project");
    QTest::newRow("depth of field, render") << QStringList{"depth-of-field"} << false;
    QTest::newRow("depth of field, project export") << QStringList{"depth-of-field"} << true;
    QTest::newRow("aerial perspective, project export")
        << QStringList{"aerial-perspective"} << true;
    QTest::newRow("aerial perspective then depth of field, project export")
        << QStringList{"aerial-perspective", "depth-of-field"} << true;
  }

  void effectFadesWithTheFringe() {
    QFETCH(QStringList, effects);
    QFETCH(bool, project);
    const FrameSize frame{kW, kH};
    const ImageF photo = stripes();
    const ProjectDepthLayer layer{"ground", brushedRegion(), anchors()};
    for (int x = 0; x < kW; ++x) {  // the scene is what the columns below assume
      QCOMPARE(layer.mask.at(std::min(x, kInside), 60), uint8_t{255});
      if (x >= kOutside) QCOMPARE(layer.mask.at(x, 60), uint8_t{0});
    }
    QVERIFY(layer.mask.at(80, 60) > 0 && layer.mask.at(80, 60) < 255);

    ImageF out;
    if (project) {
      bool has_depth = false;
      const ImageF depth = rasteriseProjectDepth({layer}, frame, nullptr, &has_depth);
      QVERIFY(has_depth);
      std::vector<EffectStep> stack;
      for (const QString& e : effects) stack.push_back(step(e));
      const DocumentArtcam camera =
          assembleDocumentArtcam(Artcam(identityImageCamera(frame)), stack, frame, has_depth);
      QVERIFY2(camera.applied.size() == stack.size(), camera.note.c_str());
      RenderSummary summary;
      LoadedImage loaded;
      loaded.image = photo;
      out = renderExport(loaded, &depth, camera.camera, {}, {}, &summary);
      QCOMPARE(summary.blurred, effects.contains("depth-of-field"));
    } else {
      const Result<InverseDepthPlane> plane =
          planeFromAnchors({layer.anchors[0], layer.anchors[1], layer.anchors[2]});
      QVERIFY(plane.ok());
      const ImageF depth = rasteriseDepth({DepthLayer{&layer.mask, *plane}}, kW, kH);
      const EffectStep s = step(effects.front());
      out = render(RenderInputs::of(photo, &depth), buildEffect(s.effect, s.values, frame));
    }
    QCOMPARE(out.width, kW);
    QCOMPARE(out.height, kH);

    const double inside = amountAt(out, photo, kInside);
    QVERIFY2(inside > 0.02, qPrintable(QString("the effect inside the region: %1").arg(inside)));
    // Over the fringe and beyond, relative to the effect inside: the largest change from one
    // column to the next, the largest effect, the largest rise outwards.
    double step = 0.0, peak = 0.0, rise = 0.0;
    int step_at = 0, peak_at = 0, rise_at = 0;
    for (int x = kInside; x < kOutside + 10; ++x) {
      const double a = amountAt(out, photo, x) / inside, next = amountAt(out, photo, x + 1) / inside;
      if (std::abs(next - a) > step) step = std::abs(next - a), step_at = x;
      if (a > peak) peak = a, peak_at = x;
      if (next - a > rise) rise = next - a, rise_at = x;
    }
    const QString figures = QString("inside %1; largest step %2 at column %3, peak %4 at %5, "
                                    "largest rise %6 at %7 (relative to inside)")
                                .arg(inside).arg(step).arg(step_at).arg(peak).arg(peak_at)
                                .arg(rise).arg(rise_at);
    qInfo("%s", qPrintable(figures));
    // No seam: one column changes the effect by at most a tenth of its full amount (the
    // smoothstep fringe, 40 px wide, falls by ~4 % per column at its steepest).
    QVERIFY2(step <= 0.1, qPrintable("a step: " + figures));
    // No peak on the fringe: the plane keeps the far point's depth there.
    QVERIFY2(peak <= 1.02, qPrintable("more effect on the fringe than inside: " + figures));
    // The coverage only falls outwards, and so does the effect.
    QVERIFY2(rise <= 0.01, qPrintable("the effect rises outwards: " + figures));
    // Where no coverage reaches, the photo is untouched.
    for (int y = 0; y < kH; ++y)
      for (int x = kOutside; x < kW; ++x)
        for (int k = 0; k < 3; ++k)
          QVERIFY2(std::abs(out.pixel(x, y)[k] - photo.pixel(x, y)[k]) <= 1e-6f,
                   qPrintable(QString("(%1, %2) channel %3").arg(x).arg(y).arg(k)));
  }
};

QTEST_GUILESS_MAIN(TestDepthFringe)
#include "test_depth_fringe.moc"
