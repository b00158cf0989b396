// SPDX-License-Identifier: Apache-2.0
// Cloud rendering: the compiled evaluator agrees with the model, dense clouds render without
// holes on a transparent background, the z-buffer keeps the nearest point whatever the thread
// count, splats follow distance, points behind the camera are dropped, RGB layers split.
// The last case times a 1-million-point cloud and prints points per second.
#include "core/cameras/effects_3d.h"
#include "core/cameras/projective_cameras.h"
#include "core/model/compiled_camera.h"
#include "core/cloud/cloud_render.h"
#include "core/cloud/sample_clouds.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <thread>

using namespace artcam;

namespace {

// An n×n grid on the plane z = depth, spanning [-half, half]², one colour.
PointCloud plane(int n, double half, double depth, const Eigen::Vector4f& colour) {
  PointCloud c;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      c.positions.emplace_back(-half + 2 * half * (i + 0.5) / n, -half + 2 * half * (j + 0.5) / n,
                               depth);
      c.colours.push_back(colour);
    }
  return c;
}

Camera frontPinhole(double focal = 2.0) {
  PinholeParams p;
  p.focal = focal;
  return pinholeCamera(p);
}

size_t opaquePixels(const ImageF& im) {
  size_t n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += im.pixel(x, y)[3] > 0;
  return n;
}

}  // namespace

class TestRender : public QObject {
  Q_OBJECT

 private slots:
  void compiledCameraMatchesTheModel() {
    // Two stages over position (4) + colour (4), random symmetric and non-symmetric entries.
    Camera cam =
        Camera::identity({Block{BlockKind::Position, 4}, Block{BlockKind::Colour, 4}}, {}, {});
    cam.stages().push_back(cam.stages()[0]);
    for (Stage& s : cam.stages())
      for (Eigen::MatrixXd& q : s.q)
        for (int r = 0; r < 8; ++r)
          for (int c = 0; c < 8; ++c) q(r, c) += test::uniform(-0.05, 0.05);
    const CompiledCamera compiled(cam);
    for (int t = 0; t < 100; ++t) {
      Eigen::VectorXd x(8);
      for (int k = 0; k < 8; ++k) x[k] = test::uniform(0.1, 1);
      x[3] = 1;
      const Eigen::VectorXd expected = cam.evaluate(x);
      CompiledCamera::Vector xv{}, yv;
      for (int k = 0; k < 8; ++k) xv[k] = x[k];
      compiled.evaluate(xv, yv);
      for (int k = 0; k < 8; ++k)
        QVERIFY(std::abs(yv[k] - expected[k]) <= 1e-12 * (1 + std::abs(expected[k])));
    }
  }

  void positionOnlyAndIdentityShortcutsChangeNothing() {
    // The renderer skips identity cameras and, in its splat-size steps, colour outputs nobody
    // reads: both must leave the image bit-identical.
    const PointCloud cube = cubeOfCubes({6});
    CloudRenderOptions o;
    o.width = o.height = 96;
    const Camera view =
        pinholeCamera(framingPinhole(cube, defaultViewPose(cloudBounds(cube)), 96, 96));
    const Camera id =
        Camera::identity({Block{BlockKind::Position, 4}, Block{BlockKind::Colour, 4}}, {}, {});
    QVERIFY(CompiledCamera(id).isIdentity());
    QVERIFY(!CompiledCamera(colourScaleEffect({})).isIdentity());
    QVERIFY(renderCloud(cube, {id}, view, o).data == renderCloud(cube, {}, view, o).data);
    const CompiledCamera cs(colourScaleEffect({}));
    CompiledCamera::Vector x{}, full, geometry;
    for (int k = 0; k < 8; ++k) x[k] = 0.1 * (k + 1);
    x[3] = 1;
    cs.evaluate(x, full);
    cs.evaluate(x, geometry, true);
    for (int k = 0; k < 3; ++k) QCOMPARE(geometry[k], full[k]);
  }

  void denseCloudRendersWithoutHolesOnTransparent() {
    // 300² points over [-1, 1]² at depth 4 with f = 2: the plane covers the central half of a
    // 200×200 image, about 0.33 px between points, so splats are at their 0.5 px minimum…
    // and at 60² points, about 1.7 px between points, the distance-sized splats must still close.
    for (const int n : {300, 60}) {
      const PointCloud c = plane(n, 1.0, 4.0, {0.5f, 0.25f, 0.1f, 1.0f});
      CloudRenderOptions o;
      o.width = o.height = 200;
      const ImageF im = renderCloud(c, {}, frontPinhole(), o);
      // The plane spans pixels 50…150; test the interior well inside the edge.
      for (int y = 52; y < 148; ++y)
        for (int x = 52; x < 148; ++x)
          QVERIFY2(im.pixel(x, y)[3] == 1.0f,
                   qPrintable(QString("hole at %1,%2 (n=%3)").arg(x).arg(y).arg(n)));
      for (const auto& [x, y] : {std::pair{2, 2}, {197, 2}, {2, 197}, {197, 197}, {100, 30}})
        QCOMPARE(im.pixel(x, y)[3], 0.0f);  // transparent background
      QCOMPARE(im.pixel(100, 100)[0], 0.5f);
    }
  }

  void zBufferKeepsTheNearestWhateverTheOrderOrThreads() {
    PointCloud far = plane(160, 2.0, 6.0, {0, 0, 1, 1});
    const PointCloud near = plane(80, 0.5, 3.0, {1, 0, 0, 1});
    PointCloud both = near;  // near first, then far appended: order must not matter
    both.positions.insert(both.positions.end(), far.positions.begin(), far.positions.end());
    both.colours.insert(both.colours.end(), far.colours.begin(), far.colours.end());
    far.positions.insert(far.positions.end(), near.positions.begin(), near.positions.end());
    far.colours.insert(far.colours.end(), near.colours.begin(), near.colours.end());
    CloudRenderOptions o;
    o.width = o.height = 128;
    o.threads = 1;
    const ImageF a = renderCloud(both, {}, frontPinhole(), o);
    o.threads = 4;
    const ImageF b = renderCloud(far, {}, frontPinhole(), o);
    QCOMPARE(a.pixel(64, 64)[0], 1.0f);  // the near red square in front
    QCOMPARE(b.pixel(64, 64)[0], 1.0f);
    QVERIFY(a.data == b.data);
    QCOMPARE(a.pixel(64, 64 - 35)[2],
             1.0f);  // blue far plane around it (near spans ±21 px, far ±42)
  }

  void splatsShrinkWithDistanceAndBehindIsDropped() {
    PointCloud c;
    c.positions = {{0, 0, 2}, {0.8, 0, 8}, {0, 0, -3}};
    CloudRenderOptions o;
    o.width = o.height = 256;
    o.point_spacing = 0.2;
    o.splat_scale = 1.0;
    o.threads = 1;
    CloudRenderSummary s;
    renderCloud(c, {}, frontPinhole(), o, &s);
    QCOMPARE(s.dropped, size_t(1));  // behind the camera
    QCOMPARE(s.drawn, size_t(2));
    // Separately: the near point's disc has 4× the radius, so about 16× the area.
    PointCloud one, other;
    one.positions = {{0, 0, 2}};
    other.positions = {{0, 0, 8}};
    const double ratio =
        static_cast<double>(opaquePixels(renderCloud(one, {}, frontPinhole(), o))) /
        static_cast<double>(opaquePixels(renderCloud(other, {}, frontPinhole(), o)));
    QVERIFY2(ratio > 12 && ratio < 20, qPrintable(QString::number(ratio)));
  }

  void rgbLayersMoveEachChannelByItsOwnScale() {
    // A white plane through chromatic aberration: red grows, blue shrinks, about the axis.
    const PointCloud c = plane(200, 1.0, 0.0, {1, 1, 1, 1});
    ChromaticAberrationParams ca;
    ca.red = 0.1;
    ca.blue = -0.1;
    OrthographicParams view;
    view.scale = 0.5;
    view.pose.centre = {0, 0, -5};
    CloudRenderOptions o;
    o.width = o.height = 200;
    o.layers = RenderLayers::Rgb;
    const ImageF im = renderCloud(c, {chromaticAberrationEffect(ca)}, orthographicCamera(view), o);
    const auto extent = [&](int channel) {
      int first = -1, last = -1;
      for (int x = 0; x < im.width; ++x)
        if (im.pixel(x, 100)[channel] > 0.5f) {
          if (first < 0) first = x;
          last = x;
        }
      return last - first + 1;
    };
    // Half-width 1 × 0.5 × 100 px = 50 px; × 1.1 and × 0.9.
    QVERIFY2(std::abs(extent(0) - 110) <= 2, qPrintable(QString::number(extent(0))));
    QVERIFY2(std::abs(extent(1) - 100) <= 2, qPrintable(QString::number(extent(1))));
    QVERIFY2(std::abs(extent(2) - 90) <= 2, qPrintable(QString::number(extent(2))));
    QCOMPARE(im.pixel(100, 100)[3], 1.0f);
  }

  void applyCamerasMatchesTheModelPointByPoint() {
    const PointCloud cube = cubeOfCubes({4});
    const Camera effect = colourScaleEffect({});
    size_t dropped = 7;
    const PointCloud out = applyCameras(cube, {effect, twistEffect({})}, 0, &dropped);
    QCOMPARE(dropped, size_t(0));
    QCOMPARE(out.size(), cube.size());
    const Camera twist = twistEffect({});
    for (size_t i = 0; i < cube.size(); i += 37) {
      Eigen::VectorXd x(8);
      x << cube.positions[i], 1.0, cube.colours[i].cast<double>();
      const Eigen::VectorXd y = effect.evaluate(x);
      const Eigen::Vector3d expected =
          twist.evaluate(Eigen::Vector4d(y[0], y[1], y[2], 1)).head<3>();
      QVERIFY((out.positions[i] - expected).norm() < 1e-12);
      QVERIFY((out.colours[i] - cube.colours[i]).norm() < 1e-6f);
    }
  }

  void progressIsReportedAndCancelHonoured() {
    const PointCloud c = plane(200, 1.0, 4.0, {1, 1, 1, 1});
    CloudRenderOptions o;
    o.width = o.height = 64;
    double last = -1;
    bool monotone = true;
    o.progress = [&](double f) {
      monotone = monotone && f >= last;
      last = f;
      return true;
    };
    CloudRenderSummary s;
    for (const RenderLayers layers : {RenderLayers::Whole, RenderLayers::Rgb}) {
      o.layers = layers;
      last = -1;
      renderCloud(c, {}, frontPinhole(), o, &s);
      QVERIFY(monotone);
      QCOMPARE(last, 1.0);
      QVERIFY(!s.cancelled);
    }
    o.progress = [](double) { return false; };
    renderCloud(c, {}, frontPinhole(), o, &s);
    QVERIFY(s.cancelled);
  }

  // Speed is the benchmark's business (`artcam bench`, never a timed test): this renders a
  // million points through both paths and checks coverage; the printed rate is information.
  void renderAMillionPoints() {
    const PointCloud cloud = cubeOfCubes({79});  // 27·6·79² = 1 010 394 points
    QVERIFY(cloud.size() > 1000000);
    CloudRenderOptions o;
    o.width = o.height = 1024;
    PinholeParams view =
        framingPinhole(cloud, defaultViewPose(cloudBounds(cloud)), o.width, o.height);
    for (const auto& [name, effects] :
         {std::pair{"projection only", std::vector<Camera>{}},
          {"twist + colour scale", std::vector<Camera>{twistEffect({}), colourScaleEffect({})}}}) {
      CloudRenderSummary s;
      const ImageF im = renderCloud(cloud, effects, pinholeCamera(view), o, &s);
      qInfo("%s: %zu points, %.1f ms, %.2f Mpoints/s on %d threads", name, s.points, s.render_ms,
            s.pointsPerSecond() / 1e6, static_cast<int>(std::thread::hardware_concurrency()));
      QVERIFY(opaquePixels(im) > 100000);
      QVERIFY(s.points >= cloud.size());  // every point went through (× 3 with RGB layers)
    }
  }
};

QTEST_GUILESS_MAIN(TestRender)
#include "test_render.moc"
