// SPDX-License-Identifier: Apache-2.0
// sourceMaps (source_maps.h), what artcam export-map writes for a camera value: a per-channel
// camera gets one map per colour channel, each the map of that channel's own position camera
// (channelCameras, what the warp renders it with); an attributed camera the map of its
// geometry with what it leaves out named; summed colour layers, positions that read colour and
// 3D cameras are refused with the reason.
#include "core/colour/colour_map.h"
#include "core/colour/colour_stage.h"
#include "core/effects/effect_table.h"
#include "core/pipeline/render.h"
#include "core/pipeline/source_maps.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <algorithm>

using namespace artcam;

namespace {

constexpr FrameSize kSize{160, 120};

Camera graded(const Camera& geometry, double gain) {
  ColourMap grade;
  grade.model = ColourModel::Linear;
  grade.m = gain * Eigen::Matrix3d::Identity();
  return withColourBlock(geometry, colourCamera(grade, kSize));
}

}  // namespace

class TestSourceMaps : public QObject {
  Q_OBJECT

 private slots:
  void aPerChannelCameraHasOneMapPerChannel() {
    const Artcam camera = buildEffect("chromatic-aberration", {{"red", {0.02}}, {"blue", {-0.02}}}, kSize);
    const std::vector<Camera> channels = channelCameras(camera);
    QCOMPARE(channels.size(), size_t{3});
    const auto maps = sourceMaps(camera, kSize);
    QVERIFY2(maps.ok(), maps.status.message.c_str());
    QCOMPARE(maps->layers.size(), size_t{3});
    const char* const names[3] = {"R", "G", "B"};
    for (size_t k = 0; k < 3; ++k) {
      QCOMPARE(maps->layers[k].name, std::string(names[k]));
      const PositionMap alone = sourcePositionMap(channels[k], kSize, kSize);
      QVERIFY(maps->layers[k].map.preimage == alone.preimage);
      QVERIFY(maps->layers[k].map.x_px == alone.x_px);
      QVERIFY(maps->layers[k].map.y_px == alone.y_px);
    }
    // R and B are scaled apart about the centre: their maps differ by about 2 % of the radius
    // at the corner.
    const PositionMap& r = maps->layers[0].map;
    const PositionMap& b = maps->layers[2].map;
    const size_t corner = r.index(0, 0);
    QVERIFY(std::abs(r.x_px[corner] - b.x_px[corner]) > 1.0f);
    QVERIFY(maps->left_out.empty());
    // The layers' union of pixels that read nothing: the red layer (scaled up) reads inside,
    // the blue (scaled down) reads past the edge at the corners.
    QVERIFY(maps->transparentPixels() >= std::max(r.transparentPixels(), b.transparentPixels()));
    QVERIFY(b.transparentPixels() > 0);
  }

  void anAttributedCameraNamesWhatItsMapLeavesOut() {
    const Camera geometry = test::randomRationalCamera(kSize, kSize, 0.05);
    const auto maps = sourceMaps(Artcam(graded(geometry, 0.8)), kSize);
    QVERIFY2(maps.ok(), maps.status.message.c_str());
    QCOMPARE(maps->layers.size(), size_t{1});
    QCOMPARE(maps->left_out, std::vector<std::string>{"colour block"});
    const PositionMap alone = sourcePositionMap(geometry, kSize, kSize);
    QVERIFY(maps->layers[0].map.x_px == alone.x_px);
    // A colour block that changes nothing leaves nothing out.
    const auto same = sourceMaps(Artcam(graded(geometry, 1.0)), kSize);
    QVERIFY2(same.ok(), same.status.message.c_str());
    QVERIFY(same->left_out.empty());
  }

  void whatNoMapCanHoldIsRefusedWithTheReason() {
    const Camera geometry = test::randomRationalCamera(kSize, kSize, 0.05);
    Artcam summed(graded(geometry, 0.5));
    summed.layers.push_back(graded(geometry, 0.25));
    auto maps = sourceMaps(summed, kSize);
    QVERIFY(!maps.ok());
    QVERIFY2(maps.status.message.find("summed") != std::string::npos, maps.status.message.c_str());
    maps = sourceMaps(buildEffect("colour-shift", {}, kSize), kSize);
    QVERIFY(!maps.ok());
    QVERIFY2(maps.status.message.find("colour or depth") != std::string::npos,
             maps.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestSourceMaps)
#include "test_source_maps.moc"
