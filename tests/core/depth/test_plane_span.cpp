// SPDX-License-Identifier: Apache-2.0
// A plane made from three points gives depths only within the span of its points' depths
// (core/depth/inverse_depth_plane.h): inside their triangle the exact affine inverse depth,
// beyond it — the rest of a painted region and the brush's soft fringe — the nearer end of the
// span, never an extrapolation. Points at 3 and 8 near one side of a brushed region once gave
// the fringe depths in the hundreds and then the raster's max depth (1/z crossed 0 there).
#include "core/depth/depth_raster.h"
#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

constexpr int kW = 200, kH = 120;

// Two points at depth 3 and one at 8, towards the fringe of the region below.
std::array<DepthAnchor, 3> anchors() {
  return {DepthAnchor{{10.0, 20.0}, 3.0}, DepthAnchor{{10.0, 100.0}, 3.0},
          DepthAnchor{{50.0, 60.0}, 8.0}};
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

}  // namespace

class TestPlaneSpan : public QObject {
  Q_OBJECT

 private slots:
  void depthStaysWithinThePointsSpan() {
    const Result<InverseDepthPlane> plane = planeFromAnchors(anchors());
    QVERIFY2(plane.ok(), plane.status.message.c_str());
    // The unbounded plane through the same points: 1/z = a·x + b·y + c (closed form here: the
    // two points at 3 share x = 10, so 1/z falls by (1/3 − 1/8)/40 per pixel in x).
    const double slope = (1.0 / 8.0 - 1.0 / 3.0) / 40.0;
    const auto affine = [&](double x) { return 1.0 / 3.0 + slope * (x - 10.0); };
    for (double y = -100.0; y <= 220.0; y += 2.5)
      for (double x = -300.0; x <= 500.0; x += 0.5) {
        const double z = 1.0 / plane->inverseDepthAt(x, y);
        QVERIFY2(z >= 3.0 * (1 - 1e-12) && z <= 8.0 * (1 + 1e-12),
                 qPrintable(QString("(%1, %2): depth %3").arg(x).arg(y).arg(z)));
        // Where the plane's own depth lies in the span it is the plane, exactly.
        const double inv = affine(x);
        if (inv >= 1.0 / 8.0 && inv <= 1.0 / 3.0)
          QVERIFY2(std::abs(plane->inverseDepthAt(x, y) - inv) <= 1e-12,
                   qPrintable(QString("(%1, %2)").arg(x).arg(y)));
      }
    // Beyond the far point it stays at the far depth, before the near one at the near depth.
    QCOMPARE(1.0 / plane->inverseDepthAt(90.0, 60.0), 8.0);
    QCOMPARE(1.0 / plane->inverseDepthAt(-40.0, 60.0), 3.0);
  }

  void aSoftFringeKeepsThePlanesDepths() {
    const RegionMask mask = brushedRegion();
    // The region has the fringe this is about: partial coverage from x ≈ 60 to 100 on row 60.
    int partial = 0;
    for (int x = 0; x < kW; ++x) partial += mask.at(x, 60) > 0 && mask.at(x, 60) < 255;
    QVERIFY2(partial >= 30, qPrintable(QString("%1 partly covered pixels").arg(partial)));
    QCOMPARE(mask.at(30, 60), uint8_t{255});
    QCOMPARE(mask.at(120, 60), uint8_t{0});

    const Result<InverseDepthPlane> plane = planeFromAnchors(anchors());
    QVERIFY(plane.ok());
    const std::vector<DepthLayer> layers{{&mask, *plane}};
    DepthRasterSummary summary;
    const ImageF depth = rasteriseDepth(layers, kW, kH, nullptr, {}, &summary);
    QVERIFY(summary.covered > 0);
    QCOMPARE(summary.clamped, size_t{0});
    QVERIFY2(summary.min_depth >= 3.0 - 1e-5 && summary.max_depth <= 8.0 + 1e-5,
             qPrintable(QString("depths %1 … %2, points at 3 and 8")
                            .arg(summary.min_depth)
                            .arg(summary.max_depth)));
    // Every partly covered pixel — the fringe — carries the far point's depth.
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const uint8_t c = mask.at(x, y);
        if (c == 0 || c == 255) continue;
        const std::optional<double> z = depthAt(depth, x, y);
        QVERIFY(z);
        QVERIFY2(std::abs(*z - 8.0) < 1e-4, qPrintable(QString("(%1, %2) coverage %3: depth %4")
                                                           .arg(x).arg(y).arg(c).arg(*z)));
      }
  }
};

QTEST_GUILESS_MAIN(TestPlaneSpan)
#include "test_plane_span.moc"
