// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 2 on the bundled house: the walls unfolded from the stereo depth
// (core/piecewise/unfold_walls.h) against an orthographic view of the same walls, ray traced
// straight at each wall point from in front of it (core/depth/stereo_house.h); and the
// refusals of rough outlines.
#include "core/depth/stereo_depth.h"
#include "core/depth/stereo_house.h"
#include "core/piecewise/unfold_walls.h"
#include "core/pipeline/render.h"

#include <Eigen/Geometry>

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

std::vector<WallOutline> outlinesOf(const StereoHousePair& pair) {
  std::vector<WallOutline> walls;
  for (const HouseWall& w : pair.walls) walls.push_back({w.name, w.left_px});
  return walls;
}

}  // namespace

class TestUnfoldWalls : public QObject {
  Q_OBJECT

  StereoHouseScene scene_;
  StereoHousePair pair_;
  ImageF stereo_depth_;

 private slots:
  void initTestCase() {
    pair_ = renderStereoHouse(scene_);
    StereoOptions options;
    options.baseline_focal = scene_.baselineFocal();
    auto depth = depthFromStereo(pair_.left, pair_.right, options);
    QVERIFY(depth.ok());
    stereo_depth_ = std::move(*depth);
  }

  void wallsMatchAnOrthographicView() {
    UnfoldOptions options;
    options.focal_px = scene_.focal_px;
    UnfoldSummary summary;
    const auto camera = unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, outlinesOf(pair_),
                                    options, &summary);
    QVERIFY2(camera.ok(), camera.status.message.c_str());
    QCOMPARE(camera->pieces->patches.size(), size_t{3});  // and the roof over the front wall
    // The walls' true sizes: front 4 × 2.2, side 3 × 3.2 (to the gable's apex).
    const double true_width[2] = {4.0, 3.0}, true_height[2] = {2.2, 3.2};
    for (int i = 0; i < 2; ++i) {
      QVERIFY2(std::abs(summary.walls[i].width - true_width[i]) < 0.03 * true_width[i],
               qPrintable(QString::number(summary.walls[i].width)));
      QVERIFY2(std::abs(summary.walls[i].height - true_height[i]) < 0.03 * true_height[i],
               qPrintable(QString::number(summary.walls[i].height)));
    }
    const ImageF out = render(RenderInputs::of(pair_.left), *camera);
    QCOMPARE(out.width, summary.size.width);
    // Each unfolded pixel against the scene seen orthogonally at the wall point it stands for
    // (the wall's own coordinates, scaled to the fitted extent so a 1 % width error does not
    // shift the comparison): 8-bit sRGB differences.
    const double s = summary.px_per_unit;
    const double tallest = std::max(summary.walls[0].height, summary.walls[1].height);
    double offset = 0.0, sum = 0.0, shifted_sum = 0.0;
    long long n = 0, wall_pixels = 0, covered = 0;
    auto srgb8 = [](double v) {
      v = std::clamp(v, 0.0, 1.0);
      return 255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
    };
    for (int i = 0; i < 2; ++i) {
      const HouseWall& wall = pair_.walls[static_cast<size_t>(i)];
      const Eigen::Vector3d c0 = wall.corners[0];
      const Eigen::Vector3d eu = (wall.corners[1] - wall.corners[0]).normalized();
      const Eigen::Vector3d ev(0, 1, 0);
      const Eigen::Vector3d normal = ev.cross(eu);  // out of the wall, towards the viewer
      const double w_est = summary.walls[static_cast<size_t>(i)].width;
      const double h_est = summary.walls[static_cast<size_t>(i)].height;
      for (int y = 0; y < out.height; ++y)
        for (int x = static_cast<int>(offset) + 4; x < static_cast<int>(offset + s * w_est) - 4;
             ++x) {
          const float* p = out.pixel(x, y);
          const double u = (x + 0.5 - offset) / (s * w_est) * true_width[i];
          const double v = (tallest - (y + 0.5) / s) / h_est * true_height[i];
          if (u < 0.05 || u > true_width[i] - 0.05 || v < 0.05 || v > true_height[i] - 0.05)
            continue;
          // Coverage below the eaves (the gable above is no rectangle): the wall is drawn up to
          // its marked outline, not to the lattice cells wholly inside it.
          if (v < 2.2 - 0.05) {
            ++wall_pixels;
            covered += p[3] >= 0.999f;
          }
          if (p[3] < 0.999f) continue;  // outside the wall, or its antialiased rim
          const Eigen::Vector3d at = c0 + u * eu + v * ev;
          const Eigen::Vector3d truth = stereoHouseColourAlong(at + 0.01 * normal, -normal);
          // A control: the same comparison a brick's width (0.4) along, which a right unfolding
          // must beat by far.
          const Eigen::Vector3d off =
              stereoHouseColourAlong(at + 0.2 * eu + 0.01 * normal, -normal);
          for (int k = 0; k < 3; ++k) {
            sum += std::abs(srgb8(p[k] / p[3]) - srgb8(truth[k]));
            shifted_sum += std::abs(srgb8(p[k] / p[3]) - srgb8(off[k]));
          }
          ++n;
        }
      offset += s * w_est;
    }
    QVERIFY(n > 20000);
    const double mean = sum / (3.0 * n), control = shifted_sum / (3.0 * n);
    qInfo(
        "unfolded walls against the orthographic view: mean |difference| %.2f/255 over %lld "
        "pixels (half a brick off: %.2f/255)",
        mean, n, control);
    QVERIFY2(mean < 12.0, qPrintable(QString::number(mean)));
    const double coverage = double(covered) / double(std::max(1LL, wall_pixels));
    qInfo("walls drawn over %.1f %% of their rectangles below the eaves (%lld px)",
          100.0 * coverage, wall_pixels);
    QVERIFY2(coverage > 0.97, qPrintable(QString::number(coverage)));
    QVERIFY2(mean < 0.6 * control, qPrintable(QString("%1 vs %2").arg(mean).arg(control)));
  }

  // The band above the front wall (2.2 tall; the gable end reaches 3.2) holds the roof seen over
  // the front wall's top edge, stretched to the picture's top. Truth: each band pixel stands for
  // a point on the front wall's plane extended upwards, between the eaves and the ridge's
  // central projection onto that plane from the left eye (the ridge is parallel to the plane,
  // so it projects to a horizontal line at a height the scene's geometry fixes), and shows what
  // the scene shows along the ray from the eye through that point.
  void roofIsStretchedOverTheShorterWall() {
    UnfoldOptions options;
    options.focal_px = scene_.focal_px;
    UnfoldSummary summary;
    const auto camera = unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, outlinesOf(pair_),
                                    options, &summary);
    QVERIFY2(camera.ok(), camera.status.message.c_str());
    QCOMPARE(camera->pieces->patches.size(), size_t{3});  // front, its roof, the gable end
    QCOMPARE(summary.walls[1].roof_height, 0.0);          // the gable is the tallest
    const HouseWall& front = pair_.walls[0];
    const Eigen::Vector3d eye = scene_.left_eye;
    const Eigen::Vector3d ridge(0.0, 3.2, 0.0);
    const double plane_z = front.corners[0].z();
    const double ridge_on_plane =
        eye.y() + (ridge.y() - eye.y()) * (plane_z - eye.z()) / (ridge.z() - eye.z());
    const double true_roof = ridge_on_plane - 2.2;
    qInfo("roof over the front wall: %.3f up its plane (truth %.3f), stretched x%.2f",
          summary.walls[0].roof_height, true_roof, summary.walls[0].roof_stretch);
    // The matcher's window carries the roof's depth a few pixels into the sky above the ridge.
    QVERIFY2(std::abs(summary.walls[0].roof_height - true_roof) < 0.1 * true_roof,
             qPrintable(QString::number(summary.walls[0].roof_height)));
    const ImageF out = render(RenderInputs::of(pair_.left), *camera);
    const double s = summary.px_per_unit;
    const double band_px =
        s * (std::max(summary.walls[0].height, summary.walls[1].height) - summary.walls[0].height);
    const Eigen::Vector3d c0 = front.corners[0];
    const Eigen::Vector3d eu = (front.corners[1] - front.corners[0]).normalized();
    auto srgb8 = [](double v) {
      v = std::clamp(v, 0.0, 1.0);
      return 255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
    };
    double sum = 0.0, control = 0.0;
    long long n = 0, empty = 0;
    const double w_est = summary.walls[0].width;
    // The right end stops 12 px short: there the photo's part of the band leans past the seam
    // with the gable end (a vertical cut in the photo) and is the gable's to show.
    for (int y = 2; y < static_cast<int>(band_px) - 2; ++y)
      for (int x = 4; x < static_cast<int>(s * w_est) - 12; ++x) {
        const float* p = out.pixel(x, y);
        if (p[3] < 0.999f) {
          ++empty;
          continue;
        }
        const double u = (x + 0.5) / (s * w_est) * 4.0;
        const double up = 1.0 - (y + 0.5) / band_px;  // 0 at the eaves, 1 at the picture's top
        const Eigen::Vector3d at = c0 + u * eu + Eigen::Vector3d(0, 2.2 + up * true_roof, 0);
        const Eigen::Vector3d truth = stereoHouseColourAlong(eye, (at - eye).normalized());
        // The control: the same pixel against the scene half a roof further up.
        const Eigen::Vector3d off = stereoHouseColourAlong(
            eye, (at + Eigen::Vector3d(0, 0.5 * true_roof, 0) - eye).normalized());
        for (int k = 0; k < 3; ++k) {
          sum += std::abs(srgb8(p[k] / p[3]) - srgb8(truth[k]));
          control += std::abs(srgb8(p[k] / p[3]) - srgb8(off[k]));
        }
        ++n;
      }
    QVERIFY2(n > 5000, qPrintable(QString("%1 band pixels drawn, %2 empty").arg(n).arg(empty)));
    QVERIFY2(empty < n / 50, qPrintable(QString("%1 band pixels empty").arg(empty)));
    const double mean = sum / (3.0 * n), shifted = control / (3.0 * n);
    qInfo(
        "roof band against the scene: mean |difference| %.2f/255 over %lld pixels (half a roof "
        "up: %.2f/255)",
        mean, n, shifted);
    QVERIFY2(mean < 12.0, qPrintable(QString::number(mean)));
    QVERIFY2(mean < 0.6 * shifted, qPrintable(QString("%1 vs %2").arg(mean).arg(shifted)));
    // Asked not to, the band stays empty.
    options.stretch_roof = false;
    const auto bare = unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, outlinesOf(pair_),
                                  options, &summary);
    QVERIFY(bare.ok());
    QCOMPARE(bare->pieces->patches.size(), size_t{2});
    QCOMPARE(summary.walls[0].roof_height, 0.0);
  }

  void refusals() {
    UnfoldOptions options;
    options.focal_px = scene_.focal_px;
    std::vector<WallOutline> walls = outlinesOf(pair_);
    // A wall marked on the sky: no depth to fix its plane.
    std::vector<WallOutline> sky{{"sky", {{10, 5}, {60, 5}, {60, 30}, {10, 30}}}};
    auto r = unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, sky, options);
    QVERIFY(!r.ok());
    QVERIFY(QString::fromStdString(r.status.message).contains("pixels with depth"));
    std::vector<WallOutline> two{{"line", {{10, 5}, {60, 5}}}};
    QVERIFY(!unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, two, options).ok());
    std::vector<WallOutline> reversed{walls[1], walls[0]};
    r = unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, reversed, options);
    QVERIFY(!r.ok());
    QVERIFY(QString::fromStdString(r.status.message).contains("left to right"));
    UnfoldOptions no_focal;
    QVERIFY(!unfoldWalls(stereo_depth_, {scene_.width, scene_.height}, walls, no_focal).ok());
  }
};

QTEST_GUILESS_MAIN(TestUnfoldWalls)
#include "test_unfold_walls.moc"
