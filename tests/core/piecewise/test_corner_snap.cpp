// SPDX-License-Identifier: Apache-2.0
// Corner snapping against boards whose corners are known exactly: an analytic checkerboard
// under a rotation and scale, and the ray-traced mirror-sphere sample (its grid corners found
// by Newton on the tracer). Flat areas and straight edges must not snap.
#include "core/piecewise/corner_snap.h"
#include "core/piecewise/sample_scenes.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace artcam;

namespace {

// A board of `square`-pixel squares turned by `angle`, 8×8 supersampled; corner (i, j) of the
// lattice is at origin + R (i, j)·square.
struct Board {
  Eigen::Vector2d origin{13.3, 17.9};
  double square = 14.0;
  double angle = 0.3;
  Eigen::Vector2d corner(int i, int j) const {
    const Eigen::Rotation2Dd r(angle);
    return origin + r * Eigen::Vector2d(i * square, j * square);
  }
  ImageF render(int w, int h) const {
    ImageF img(w, h, 1);
    const Eigen::Rotation2Dd back(-angle);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double v = 0;
        for (int s = 0; s < 64; ++s) {
          const Eigen::Vector2d p(x + (s % 8 + 0.5) / 8, y + (s / 8 + 0.5) / 8);
          const Eigen::Vector2d q = back * (p - origin) / square;
          v += (static_cast<int>(std::floor(q.x())) + static_cast<int>(std::floor(q.y()))) % 2 ? 0.9 : 0.1;
        }
        img.pixel(x, y)[0] = static_cast<float>(v / 64);
      }
    return img;
  }
};

}  // namespace

class TestCornerSnap : public QObject {
  Q_OBJECT

 private slots:
  void snapsToAnalyticCorners() {
    const Board board;
    const ImageF image = board.render(200, 200);
    double worst = 0;
    int tried = 0;
    for (int j = 1; j <= 8; ++j)
      for (int i = 1; i <= 8; ++i) {
        const Eigen::Vector2d truth = board.corner(i, j);
        if (truth.minCoeff() < 15 || truth.maxCoeff() > 185) continue;
        const Eigen::Vector2d click = truth + Eigen::Vector2d(test::uniform(-3, 3), test::uniform(-3, 3));
        const auto snapped = snapToGridCorner(image, click);
        QVERIFY2(snapped, qPrintable(QString("corner %1,%2 not found").arg(i).arg(j)));
        worst = std::max(worst, (*snapped - truth).norm());
        ++tried;
      }
    std::printf("analytic board: %d corners, worst %.4f px\n", tried, worst);
    QVERIFY(tried >= 20);
    QVERIFY2(worst < 0.05, qPrintable(QString::number(worst)));
  }

  void snapsInTheRayTracedReflection() {
    MirrorSphereScene scene;
    // Twice the bundled sample's resolution, as a user would shoot a calibration photo.
    scene.photo_width = 1280;
    scene.photo_height = 960;
    scene.focal_px = 0.9 * 1280;
    scene.floor_centre_z = 1.6;
    const SampleScene sample = makeMirrorSphereSample(scene, 24);
    // Corners whose neighbours are at least 8 px away in the photo: a user can click those.
    double worst = 0;
    std::vector<double> errors;
    int tried = 0;
    for (const PointMatch& m : sample.grid_matches) {
      // The board's outer corners meet the table, not four squares: not X-corners.
      if (m.source.minCoeff() < 1.0 || m.source.maxCoeff() > 511.0) continue;
      double nearest = 1e9;
      for (const PointMatch& n : sample.grid_matches)
        if (&n != &m) nearest = std::min(nearest, (n.target - m.target).norm());
      if (nearest < 8.0) continue;
      const Eigen::Vector2d truth = m.target;
      CornerSnapOptions o;
      o.search_radius_px = 2.5;
      o.window_radius_px = 3.0;
      const auto snapped = snapToGridCorner(sample.photo, truth + Eigen::Vector2d(1.2, -0.9), o);
      QVERIFY(snapped);
      worst = std::max(worst, (*snapped - truth).norm());
      errors.push_back((*snapped - truth).norm());
      ++tried;
    }
    std::sort(errors.begin(), errors.end());
    const double median = errors.empty() ? 0.0 : errors[errors.size() / 2];
    std::printf("mirror sphere sample: %d of %zu corners, median %.4f px, worst %.4f px\n", tried,
                sample.grid_matches.size(), median, worst);
    QVERIFY(tried >= 20);
    // The sample photo is 3×3 supersampled, so its edges sit on a 1/3 px lattice, and the
    // reflected squares are strongly sheared: a tenth of a pixel is what the image holds.
    QVERIFY2(median < 0.12, qPrintable(QString::number(median)));
    QVERIFY2(worst < 0.3, qPrintable(QString::number(worst)));
  }

  void flatAndEdgesDoNotSnap() {
    ImageF flat(64, 64, 3);
    for (float& v : flat.data) v = 0.5f;
    QVERIFY(!snapToGridCorner(flat, {32, 32}));
    ImageF edge(64, 64, 1);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) edge.pixel(x, y)[0] = x < 32 ? 0.1f : 0.9f;
    QVERIFY(!snapToGridCorner(edge, {32, 30}));
    ImageF noise(64, 64, 1);
    for (float& v : noise.data) v = static_cast<float>(0.5 + test::uniform(-0.01, 0.01));
    QVERIFY(!snapToGridCorner(noise, {32, 32}));
  }
};

QTEST_GUILESS_MAIN(TestCornerSnap)
#include "test_corner_snap.moc"
