// SPDX-License-Identifier: Apache-2.0
// The edge-aware brush against hand-drawn truths: a photo of two flat colours meeting at a
// vertical edge, and one with a thin stripe cutting a same-coloured area in two.
#include "core/depth/edge_aware_brush.h"
#include "core/depth/region_mask.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

// Columns x < edge are dark grey, the rest light; `stripe` columns [s0, s1) are light too.
ImageF twoTone(int w, int h, int edge, int s0 = -1, int s1 = -1) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool light = x >= edge || (x >= s0 && x < s1);
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = light ? 0.9f : 0.1f;
    }
  return img;
}

}  // namespace

class TestEdgeAwareBrush : public QObject {
  Q_OBJECT

 private slots:
  void strokeAlongAnEdgeStaysOnItsSide() {
    const ImageF photo = twoTone(100, 60, 50);
    const BrushOptions brush{15.0, 1.0, false};  // hard: coverage is 0 or 255
    EdgeAwareOptions edges;
    edges.reference = photoColourAt(photo, 45, 30);
    QCOMPARE(edges.reference.x(), 0.1f);
    RegionMask aware(100, 60), plain(100, 60);
    stampEdgeAware(aware, photo, {45.5, 40.5}, brush, edges);
    segmentEdgeAware(aware, photo, {45.5, 40.5}, {45.5, 20.5}, brush, edges);
    plain.stamp({45.5, 40.5}, brush);
    plain.segment({45.5, 40.5}, {45.5, 20.5}, brush);
    // Truth from the plain brush (another path): the same dabs, clipped to the dark side
    // (every dab's disc meets the dark side in one convex, so connected, piece).
    for (int y = 0; y < 60; ++y)
      for (int x = 0; x < 100; ++x)
        QCOMPARE(aware.at(x, y), x < 50 ? plain.at(x, y) : uint8_t{0});
    // And the sweep itself by hand: the disc at the stroke's ends and the middle of its path.
    QCOMPARE(aware.at(45, 54), uint8_t{255});  // 14 px below the first dab
    QCOMPARE(aware.at(45, 6), uint8_t{255});   // 14 px above the last
    QCOMPARE(aware.at(31, 30), uint8_t{255});  // 14 px left of the path
    QCOMPARE(aware.at(45, 57), uint8_t{0});    // beyond the radius
    QCOMPARE(aware.at(49, 30), uint8_t{255});
    QCOMPARE(plain.at(55, 30), uint8_t{255});  // without it the brush does cross
  }

  void sameColourBehindAnEdgeIsNotReached() {
    // Dark | light stripe at x ∈ [40, 43) | dark: the far dark part is within the disc and of
    // the reference colour, but not connected to the centre.
    const ImageF photo = twoTone(100, 60, 80, 40, 43);
    const BrushOptions brush{12.0, 1.0, false};
    EdgeAwareOptions edges;
    edges.reference = photoColourAt(photo, 35, 30);
    RegionMask mask(100, 60);
    stampEdgeAware(mask, photo, {35.5, 30.5}, brush, edges);
    QCOMPARE(mask.at(35, 30), uint8_t{255});
    QCOMPARE(mask.at(39, 30), uint8_t{255});
    QCOMPARE(mask.at(41, 30), uint8_t{0});  // the stripe: another colour
    QCOMPARE(mask.at(44, 30), uint8_t{0});  // same colour, cut off by the stripe
    // A dab centred on another colour paints nothing.
    RegionMask none(100, 60);
    QVERIFY(stampEdgeAware(none, photo, {41.5, 30.5}, brush, edges).width() > 0);
    QCOMPARE(none.coveredCount(), size_t{0});
    // A wide tolerance takes the light stripe too, and so reaches the far side.
    edges.tolerance = 1.5;
    RegionMask wide(100, 60);
    stampEdgeAware(wide, photo, {35.5, 30.5}, brush, edges);
    QCOMPARE(wide.at(44, 30), uint8_t{255});
  }
};

QTEST_GUILESS_MAIN(TestEdgeAwareBrush)
#include "test_edge_aware_brush.moc"
