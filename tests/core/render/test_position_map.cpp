// SPDX-License-Identifier: Apache-2.0
// sourcePositionMap (position_map.h), what artcam export-map writes: its positions are the exact
// double-precision reference inverse (makeReferenceInverse, Newton to ~1e-7 px with no seed and
// no float) to 1e-3 px and have a preimage on the same pixels; a camera that also changes colour
// maps exactly as its geometry alone; a camera whose positions read colour is refused.
#include "core/colour/colour_map.h"
#include "core/colour/colour_stage.h"
#include "core/effects/chromatic.h"
#include "core/effects/effect_table.h"
#include "core/model/structure.h"
#include "core/render/position_map.h"
#include "core/render/warp.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <stdexcept>

using namespace artcam;

class TestPositionMap : public QObject {
  Q_OBJECT

 private slots:
  void matchesTheReferenceInverse_data() {
    QTest::addColumn<double>("strength");
    QTest::addColumn<int>("map_width");
    QTest::newRow("mild, same size") << 0.05 << 160;
    QTest::newRow("strong, same size") << 0.12 << 160;
    QTest::newRow("mild, twice the size") << 0.05 << 320;
  }
  void matchesTheReferenceInverse() {
    QFETCH(double, strength);
    QFETCH(int, map_width);
    const FrameSize source{160, 120};
    const FrameSize target{map_width, map_width * 3 / 4};
    const Camera camera = test::randomRationalCamera(source, source, strength);
    const PositionMap map = sourcePositionMap(camera, source, target);
    QCOMPARE(map.kernel, std::string("rational"));
    QCOMPARE(map.x_px.size(), size_t(target.width) * size_t(target.height));
    const auto reference =
        makeReferenceInverse(camera, analyseStructure(camera), source, target, true);
    std::vector<Eigen::Vector2d> row(static_cast<size_t>(target.width));
    std::vector<unsigned char> valid(static_cast<size_t>(target.width));
    double worst = 0.0;
    long long with = 0, counted_invalid = 0;
    for (int y = 0; y < target.height; ++y) {
      reference->row(y, target.width, row.data(), valid.data());
      for (int x = 0; x < target.width; ++x) {
        const size_t k = map.index(x, y);
        QCOMPARE(map.preimage[k] != Preimage::None, valid[static_cast<size_t>(x)] != 0);
        if (!valid[static_cast<size_t>(x)]) {
          ++counted_invalid;
          continue;
        }
        ++with;
        worst = std::max(
            worst,
            (Eigen::Vector2d(map.x_px[k], map.y_px[k]) - row[static_cast<size_t>(x)]).norm());
      }
    }
    qInfo("%lld pixels, worst %.3g px from the reference inverse", with, worst);
    QVERIFY(with > target.width * target.height / 2);
    QCOMPARE(map.invalid_pixels, counted_invalid);
    QVERIFY(worst < 1e-3);
  }

  void aColourBlockDoesNotMovePixels() {
    const FrameSize size{160, 120};
    const Camera geometry = test::randomRationalCamera(size, size, 0.08);
    ColourMap grade;
    grade.model = ColourModel::Linear;
    grade.m = 0.8 * Eigen::Matrix3d::Identity();
    const Camera graded = withColourBlock(geometry, colourCamera(grade, size));
    QVERIFY(graded.blocks().size() == 2);
    const PositionMap a = sourcePositionMap(geometry, size, size);
    const PositionMap b = sourcePositionMap(graded, size, size);
    QVERIFY(a.preimage == b.preimage);
    QVERIFY(a.x_px == b.x_px);
    QVERIFY(a.y_px == b.y_px);
  }

  // The map's rule for pixels that read nothing is the warp's own: a constant photo warped
  // through a strong barrel (its corners read beyond the photo, and past the pole curve there
  // is no preimage) has alpha 0 exactly where the map says None or OutsidePhoto. The truth is
  // the warp's output alpha, the span sampler's coverage, not the map's code.
  void readsThePhotoExactlyWhereTheWarpHasAlpha() {
    const FrameSize source{160, 120}, target{240, 180};
    const Camera camera = buildEffect("barrel", {{"k", {-0.3}}}, source).main();
    const PositionMap map = sourcePositionMap(camera, source, target);
    ImageF photo(source.width, source.height, 3);
    std::fill(photo.data.begin(), photo.data.end(), 0.5f);
    WarpOptions options;
    options.width = target.width;
    options.height = target.height;
    options.coordinates.certify_tolerance_px = 0.0;  // the map's positions, bit for bit
    WarpSummary summary;
    const ImageF out = warpImage(photo, camera, options, &summary);
    QCOMPARE(out.alpha_channel, 3);
    long long disagree = 0;
    for (int y = 0; y < target.height; ++y)
      for (int x = 0; x < target.width; ++x)
        disagree += (out.pixel(x, y)[3] > 0.0f) != (map.preimage[map.index(x, y)] == Preimage::InPhoto);
    qInfo("no preimage %lld, outside the photo %lld, warp transparent %lld", map.invalid_pixels,
          map.outside_pixels, summary.transparent_pixels);
    QCOMPARE(disagree, 0LL);
    QCOMPARE(map.transparentPixels(), summary.transparent_pixels);
    QVERIFY(map.outside_pixels > 1000);
    // Outside-photo pixels keep their position: more than half a pixel off the frame.
    for (size_t k = 0; k < map.preimage.size(); ++k)
      if (map.preimage[k] == Preimage::OutsidePhoto)
        QVERIFY(map.x_px[k] <= -0.5f || map.y_px[k] <= -0.5f || map.x_px[k] >= source.width + 0.5f ||
                map.y_px[k] >= source.height + 0.5f);
  }

  void positionsThatReadColourAreRefused() {
    const FrameSize size{160, 120};
    const std::vector<Camera> layers = colourShiftLayers({}, size, size);
    QVERIFY(!layers.empty());
    QVERIFY(analyseStructure(layers.front()).geometry_depends_on_attributes);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sourcePositionMap(layers.front(), size, size));
  }
};

QTEST_GUILESS_MAIN(TestPositionMap)
#include "test_position_map.moc"
