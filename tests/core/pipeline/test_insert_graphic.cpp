// SPDX-License-Identifier: Apache-2.0
// Fig 7 end to end against the ray tracer: the mirror-sphere sample's grid matches and four
// clicked table corners fit the reflection's piecewise camera and the table's homography, and
// insertGraphic puts a graphic in both places. The graphic encodes its own coordinates (red and
// green ramps), so every output pixel says which graphic point landed there; the tracer says
// which one should have (directly on the table, or reflected in the sphere), and the difference,
// taken back to photo pixels through the tracer's own Jacobian, is the error.
#include "core/piecewise/piecewise_fit.h"
#include "core/piecewise/sample_scenes.h"
#include "core/pipeline/insert_graphic.h"

#include <QtTest/QtTest>

#include <Eigen/Dense>

#include <cmath>
#include <optional>

using namespace artcam;

namespace {

constexpr int kW = 320, kH = 240, kGraphic = 512;
constexpr float kGraphicBlue = 0.25f;

MirrorSphereScene sampleScene() {  // as `artcam sample mirror-sphere --size 320x240` sets it
  MirrorSphereScene scene;
  scene.photo_width = kW;
  scene.photo_height = kH;
  scene.focal_px = 0.9 * kW;
  scene.floor_centre_z = 1.6;
  return scene;
}

// The graphic: red = u / 512, green = v / 512 at its pixel centres, opaque.
ImageF coordinateGraphic() {
  ImageF g(kGraphic, kGraphic, 4, 3);
  for (int y = 0; y < kGraphic; ++y)
    for (int x = 0; x < kGraphic; ++x) {
      float* p = g.pixel(x, y);
      p[0] = static_cast<float>((x + 0.5) / kGraphic);
      p[1] = static_cast<float>((y + 0.5) / kGraphic);
      p[2] = kGraphicBlue;
      p[3] = 1.0f;
    }
  return g;
}

// A photo that the graphic cannot be mistaken for: pure blue.
ImageF bluePhoto() {
  ImageF photo(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) photo.pixel(x, y)[2] = 1.0f;
  return photo;
}

enum class Seen { Nothing, Table, Reflection };

// What the photo ray through p sees of the graphic, with a margin inside its edges.
Seen seen(const MirrorSphereScene& scene, const Eigen::Vector2d& p, Eigen::Vector2d* graphic_px) {
  const TracedRay r = scene.trace(p);
  if (!r.on_plane) return Seen::Nothing;
  const Eigen::Vector2d& g = r.plane_px;
  if (graphic_px) *graphic_px = g;
  if (g.x() < 0 || g.y() < 0 || g.x() > kGraphic || g.y() > kGraphic) return Seen::Nothing;
  return r.through_object ? Seen::Reflection : Seen::Table;
}

// The pixel and its eight neighbours see the same kind, well inside the graphic: away from
// every edge where filters blend two kinds.
std::optional<Seen> interior(const MirrorSphereScene& scene, int x, int y) {
  std::optional<Seen> kind;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      Eigen::Vector2d g;
      const Seen s = seen(scene, {x + dx + 0.5, y + dy + 0.5}, &g);
      if (s != Seen::Nothing && (g.x() < 3 || g.y() < 3 || g.x() > kGraphic - 3 || g.y() > kGraphic - 3))
        return std::nullopt;
      if (kind && *kind != s) return std::nullopt;
      kind = s;
    }
  return kind;
}

// Photo-pixel error of a decoded graphic point: the graphic-pixel difference through the
// inverse of the tracer's Jacobian d(graphic)/d(photo) at the pixel centre.
double photoError(const MirrorSphereScene& scene, const Eigen::Vector2d& p,
                  const Eigen::Vector2d& truth, const Eigen::Vector2d& decoded) {
  const double h = 0.01;
  Eigen::Matrix2d j;
  for (int a = 0; a < 2; ++a) {
    const Eigen::Vector2d e = Eigen::Vector2d::Unit(a) * h;
    j.col(a) = (scene.trace(p + e).plane_px - scene.trace(p - e).plane_px) / (2 * h);
  }
  return (j.inverse() * (decoded - truth)).norm();
}

struct Fig7 {
  MirrorSphereScene scene = sampleScene();
  SampleScene sample;
  InsertionCameras cameras;
};

Fig7 fitFig7() {
  Fig7 f;
  f.sample = makeMirrorSphereSample(f.scene, 24);
  PiecewiseOptions options;
  options.max_error_px = 0.3;
  const PiecewiseSummary fit = fitPiecewise(f.sample.grid_matches, {kGraphic, kGraphic}, {kW, kH}, options);
  if (!fit.status) qFatal("piecewise fit: %s", fit.status.message.c_str());
  f.cameras.object = fit.camera;
  const FitSummary table = fitBoardHomography(f.sample.table_matches, {kGraphic, kGraphic}, {kW, kH});
  if (!table.status) qFatal("table homography: %s", table.status.message.c_str());
  f.cameras.plane = table.camera;
  f.cameras.region = f.sample.region;
  return f;
}

}  // namespace

class TestInsertGraphic : public QObject {
  Q_OBJECT

 private slots:
  void theSampleClicksFourVisibleTableCorners() {
    const Fig7 f = fitFig7();
    QCOMPARE(f.sample.table_matches.size(), size_t(4));
    for (const PointMatch& m : f.sample.table_matches) {
      // Each click sees that very board point directly, not through the sphere.
      const TracedRay r = f.scene.trace(m.target);
      QVERIFY(r.on_plane && !r.through_object);
      QVERIFY2((r.plane_px - m.source).norm() < 1e-6, qPrintable(QString::number((r.plane_px - m.source).norm())));
    }
    // The outline's vertices lie on the silhouette: just inside meets the sphere, just outside not.
    const Eigen::Vector2d c = f.scene.objectCentrePx();
    for (const Eigen::Vector2d& v : f.sample.region) {
      const Eigen::Vector2d out = (v - c).normalized();
      QVERIFY(f.scene.trace(v - 1e-3 * out).through_object);
      QVERIFY(!f.scene.trace(v + 1e-3 * out).through_object);
    }
  }

  void graphicLandsOnTheTableAndInItsReflection() {
    const Fig7 f = fitFig7();
    InsertSummary summary;
    const ImageF out = insertGraphic(bluePhoto(), coordinateGraphic(), f.cameras, {}, &summary);
    QCOMPARE(out.width, kW);
    QCOMPARE(out.height, kH);

    int table = 0, reflection = 0, nothing = 0, uncalibrated = 0;
    double table_worst = 0, reflection_worst = 0, reflection_sq = 0;
    for (int y = 1; y < kH - 1; ++y)
      for (int x = 1; x < kW - 1; ++x) {
        const std::optional<Seen> kind = interior(f.scene, x, y);
        if (!kind) continue;
        const float* p = out.pixel(x, y);
        const Eigen::Vector2d centre(x + 0.5, y + 0.5);
        if (*kind == Seen::Nothing) {
          // Untouched: the blue photo exactly, also where the sphere hides the board.
          QVERIFY2(p[0] == 0.0f && p[1] == 0.0f && p[2] == 1.0f,
                   qPrintable(QString("pixel %1,%2 changed").arg(x).arg(y)));
          ++nothing;
          continue;
        }
        Eigen::Vector2d truth;
        seen(f.scene, centre, &truth);
        if (*kind == Seen::Reflection && !f.cameras.object.targetPixelFromSourcePixel(truth)) {
          ++uncalibrated;  // beyond the grid corners the tracer could find near the rim
          continue;
        }
        QVERIFY2(std::abs(p[2] - kGraphicBlue) < 1e-3,
                 qPrintable(QString("pixel %1,%2 not covered: blue %3").arg(x).arg(y).arg(p[2])));
        const Eigen::Vector2d decoded(p[0] * kGraphic, p[1] * kGraphic);
        const double e = photoError(f.scene, centre, truth, decoded);
        if (*kind == Seen::Table) {
          ++table;
          table_worst = std::max(table_worst, e);
        } else {
          ++reflection;
          reflection_worst = std::max(reflection_worst, e);
          reflection_sq += e * e;
        }
      }
    const double reflection_rms = std::sqrt(reflection_sq / std::max(1, reflection));
    qInfo("table %d px (max %.2g px), reflection %d px (max %.3f, RMS %.3f px), untouched %d px, "
          "reflection beyond the calibrated grid %d px",
          table, table_worst, reflection, reflection_worst, reflection_rms, nothing, uncalibrated);
    QVERIFY(uncalibrated < reflection / 10);
    QVERIFY(table > 20000);
    QVERIFY(reflection > 2000);
    // The homography from four exact clicks is exact; what is left is the filter.
    QVERIFY2(table_worst < 0.05, qPrintable(QString::number(table_worst)));
    // The piecewise camera's own bound at the matches is 0.3 px; between them a little more.
    QVERIFY2(reflection_worst < 0.6, qPrintable(QString::number(reflection_worst)));
    QVERIFY2(reflection_rms < 0.2, qPrintable(QString::number(reflection_rms)));
  }

  void theSphereHidesTheTablesCopy() {
    // Sphere pixels whose straight ray would meet the board behind the sphere. A half-transparent
    // graphic lets the table's copy show through the reflection's: with the region these pixels
    // are what the reflection alone makes of them; without, the table's copy darkens them.
    Fig7 f = fitFig7();
    ImageF half = coordinateGraphic();
    for (float& v : half.data) v *= 0.5f;  // premultiplied: colour and alpha together
    std::vector<Eigen::Vector2i> hidden;
    for (int y = 1; y < kH - 1; ++y)
      for (int x = 1; x < kW - 1; ++x) {
        bool all_hidden = true;
        for (int dy = -1; dy <= 1 && all_hidden; ++dy)
          for (int dx = -1; dx <= 1 && all_hidden; ++dx) {
            const Eigen::Vector2d q(x + dx + 0.5, y + dy + 0.5);
            const Eigen::Vector3d d = f.scene.rayDirection(q);
            if (!f.scene.trace(q).through_object || d.y() >= 0.0) {
              all_hidden = false;
              break;
            }
            const Eigen::Vector2d g = f.scene.floorPx(f.scene.eye + (-f.scene.eye.y() / d.y()) * d);
            all_hidden = g.x() > 3 && g.y() > 3 && g.x() < kGraphic - 3 && g.y() < kGraphic - 3;
          }
        if (all_hidden) hidden.emplace_back(x, y);
      }
    const ImageF with_region = insertGraphic(bluePhoto(), half, f.cameras);
    f.cameras.region.clear();
    const ImageF without_region = insertGraphic(bluePhoto(), half, f.cameras);
    f.cameras.plane.reset();
    const ImageF reflection_only = insertGraphic(bluePhoto(), half, f.cameras);
    int shown_with = 0, shown_without = 0;
    for (const Eigen::Vector2i& px : hidden) {
      const float alone = reflection_only.pixel(px.x(), px.y())[2];
      shown_with += with_region.pixel(px.x(), px.y())[2] != alone;
      shown_without += without_region.pixel(px.x(), px.y())[2] < alone - 0.05f;
    }
    qInfo("sphere pixels hiding the board: %zu; the table's copy shows on %d with the region, %d without",
          hidden.size(), shown_with, shown_without);
    QVERIFY(hidden.size() > 100);
    QCOMPARE(shown_with, 0);
    QVERIFY(shown_without > int(hidden.size()) / 2);
  }

  void collinearClicksAreRefused() {
    std::vector<PointMatch> clicks;
    for (int i = 0; i < 4; ++i) {
      PointMatch m;
      m.source = Eigen::Vector2d(100.0 * i, 100.0 * i);  // the board's diagonal
      m.target = Eigen::Vector2d(10.0 + 50.0 * i, 20.0 + 30.0 * i);
      clicks.push_back(m);
    }
    const FitSummary fit = fitBoardHomography(clicks, {512, 512}, {kW, kH});
    QVERIFY(!fit.status);
    QVERIFY(!fit.status.message.empty());
  }
};

QTEST_GUILESS_MAIN(TestInsertGraphic)
#include "test_insert_graphic.moc"
