// SPDX-License-Identifier: Apache-2.0
// Depth from a stereo pair (core/depth/stereo_depth.h) against the ray traced truth of the
// bundled house (core/depth/stereo_house.h), whose own depth is checked against the pinhole
// projection of the house's corners; and the matcher's refusals.
#include "core/depth/stereo_depth.h"
#include "core/depth/stereo_house.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace artcam;

class TestStereoDepth : public QObject {
  Q_OBJECT

  StereoHouseScene scene_;
  StereoHousePair pair_;

 private slots:
  void initTestCase() {
    scene_.width = 480;
    scene_.height = 360;
    scene_.focal_px = 420.0;
    pair_ = renderStereoHouse(scene_);
  }

  void truthIsThePinholesDepth() {
    // A point inside the front wall, projected by hand: the traced depth there is its distance
    // along the view axis.
    const Eigen::Vector3d X(0.3, 0.6, 1.5);
    const Eigen::Vector3d v = X - scene_.left_eye;
    const double z = v.dot(scene_.forward());
    const double x = 0.5 * scene_.width + scene_.focal_px * v.dot(scene_.right()) / z;
    const double y = 0.5 * scene_.height + scene_.focal_px * v.dot(scene_.down()) / z;
    const float traced = *pair_.left_depth.pixel(static_cast<int>(x), static_cast<int>(y));
    QVERIFY2(std::abs(traced - z) < 0.02 * z, qPrintable(QString("%1 vs %2").arg(traced).arg(z)));
    QCOMPARE(*pair_.left_depth.pixel(scene_.width / 2, 2), 0.0f);  // sky
    QCOMPARE(pair_.walls.size(), size_t{2});
    QCOMPARE(pair_.walls[1].left_px.size(), size_t{5});  // the gable's apex
  }

  void matchesTheTracedDepth() {
    StereoOptions options;
    options.baseline_focal = scene_.baselineFocal();
    StereoSummary summary;
    const auto depth = depthFromStereo(pair_.left, pair_.right, options, &summary);
    QVERIFY2(depth.ok(), depth.status.message.c_str());
    QCOMPARE(depth->width, scene_.width);
    std::vector<double> relative;
    long long truth_pixels = 0, sky = 0, sky_with_depth = 0;
    for (int y = 0; y < scene_.height; ++y)
      for (int x = summary.max_disparity; x < scene_.width; ++x) {
        const float t = *pair_.left_depth.pixel(x, y);
        const float e = *depth->pixel(x, y);
        QVERIFY(std::isfinite(e) && e >= 0.0f);
        if (t <= 0.0f) {
          ++sky;
          if (e > 0.0f) ++sky_with_depth;
          continue;
        }
        ++truth_pixels;
        if (e > 0.0f) relative.push_back(std::abs(e - t) / t);
      }
    std::sort(relative.begin(), relative.end());
    const double median = relative[relative.size() / 2];
    const double p90 = relative[relative.size() * 9 / 10];
    const double share = static_cast<double>(relative.size()) / truth_pixels;
    qInfo(
        "stereo house %dx%d: median relative depth error %.4f, 90th percentile %.4f, %.1f%% "
        "of the surfaces matched",
        scene_.width, scene_.height, median, p90, 100 * share);
    QVERIFY2(median < 0.02, qPrintable(QString::number(median)));
    QVERIFY2(p90 < 0.06, qPrintable(QString::number(p90)));
    QVERIFY2(share > 0.9, qPrintable(QString::number(share)));
    // The textureless sky gets no depth, but for a rim the matcher's window spans: keeping every
    // match, it carries the roof's depth tens of pixels into the sky.
    StereoOptions every_match = options;
    every_match.min_texture = 0.0;
    const auto spread = depthFromStereo(pair_.left, pair_.right, every_match);
    QVERIFY(spread.ok());
    long long spread_sky = 0;
    for (int y = 0; y < scene_.height; ++y)
      for (int x = summary.max_disparity; x < scene_.width; ++x)
        if (*pair_.left_depth.pixel(x, y) <= 0.0f && *spread->pixel(x, y) > 0.0f) ++spread_sky;
    const double sky_share = static_cast<double>(sky_with_depth) / sky;
    const double spread_share = static_cast<double>(spread_sky) / sky;
    qInfo("sky with a depth: %.2f%% of %lld pixels (every match kept: %.2f%%)", 100 * sky_share,
          sky, 100 * spread_share);
    QVERIFY2(sky_share < 0.05, qPrintable(QString::number(sky_share)));
    QVERIFY2(sky_share < 0.25 * spread_share,
             qPrintable(QString("%1 vs %2").arg(sky_share).arg(spread_share)));
  }

  void refusals() {
    StereoOptions options;
    options.baseline_focal = 100.0;
    ImageF small(100, 80, 3);
    QVERIFY(!depthFromStereo(pair_.left, small, options).ok());
    QVERIFY(QString::fromStdString(depthFromStereo(pair_.left, small, options).status.message)
                .contains("one size"));
    StereoOptions no_scale;
    QVERIFY(!depthFromStereo(pair_.left, pair_.right, no_scale).ok());
    StereoOptions even = options;
    even.block_size = 4;
    QVERIFY(!depthFromStereo(pair_.left, pair_.right, even).ok());
    StereoOptions wide = options;
    wide.max_disparity = 1024;
    QVERIFY(QString::fromStdString(depthFromStereo(pair_.left, pair_.right, wide).status.message)
                .contains("not below the width"));
    // A pair with nothing to match: refused, not a map of zeros passed off as depth.
    ImageF grey(200, 100, 3);
    std::fill(grey.data.begin(), grey.data.end(), 0.5f);
    const auto flat = depthFromStereo(grey, grey, options);
    QVERIFY(!flat.ok());
    QVERIFY(QString::fromStdString(flat.status.message).contains("no pixel"));
  }
};

QTEST_GUILESS_MAIN(TestStereoDepth)
#include "test_stereo_depth.moc"
