// SPDX-License-Identifier: Apache-2.0
// The paper's Fig 1, measured on the sample cloud resources/cube.ply (the 3×3×3 cube of cubes
// written by `artcam preset cube-of-cubes`): each effect does what the caption says, in
// numbers taken from the moved cloud and from renders.
#include "core/cameras/effects_3d.h"
#include "core/cameras/projective_cameras.h"
#include "core/cloud/cloud_render.h"
#include "core/cloud/sample_clouds.h"
#include "core/io/ply.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

// The head-on views: looking along +z from (0, 0, -5) at the centre.
CameraPose headOn() { return CameraPose::lookAt({0, 0, -5}, {0, 0, 0}); }

Camera headOnOrthographic() {
  OrthographicParams o;
  o.scale = 0.3;
  o.pose = headOn();
  return orthographicCamera(o);
}

CloudRenderOptions small() {
  CloudRenderOptions o;
  o.width = o.height = 256;
  return o;
}

// Silhouette width (opaque pixels from first to last) of every row; 0 for empty rows.
std::vector<int> rowWidths(const ImageF& im, int channel = 3, float threshold = 0.0f) {
  std::vector<int> w(im.height, 0);
  for (int y = 0; y < im.height; ++y) {
    int first = -1, last = -1;
    for (int x = 0; x < im.width; ++x)
      if (im.pixel(x, y)[channel] > threshold) {
        if (first < 0) first = x;
        last = x;
      }
    w[y] = first < 0 ? 0 : last - first + 1;
  }
  return w;
}

int maxOf(const std::vector<int>& v) { return *std::max_element(v.begin(), v.end()); }

// Index of the small cube a sample point belongs to, from its original position.
Eigen::Vector3i cubeOf(const Eigen::Vector3d& p) {
  return ((p / (2.0 / 3.0)).array().round() + 1).cast<int>();
}

}  // namespace

class TestFig1 : public QObject {
  Q_OBJECT

  PointCloud cube_;

 private slots:
  void initTestCase() {
    const auto cube = readPly(test::resourcePath("cube.ply"));
    QVERIFY2(cube.ok(), cube.status.message.c_str());
    cube_ = *cube;
  }

  void sampleCloudIsTheGeneratorsOutput() {
    // resources/cube.ply must be what the code makes (float positions, uchar sRGB colours).
    const PointCloud made = cubeOfCubes();
    QCOMPARE(cube_.size(), made.size());
    QCOMPARE(cube_.size(), size_t(27 * 6 * 100));
    for (size_t i = 0; i < made.size(); ++i) {
      QVERIFY((cube_.positions[i] - made.positions[i]).norm() < 1e-6);
      QVERIFY((cube_.colours[i] - made.colours[i]).norm() < 4e-3f);
    }
  }

  void originalShowsThreeFacesOfAFramedCube() {
    const CameraPose pose = defaultViewPose(cloudBounds(cube_));
    const ImageF im =
        renderCloud(cube_, {}, pinholeCamera(framingPinhole(cube_, pose, 256, 256)), small());
    QCOMPARE(im.pixel(128, 128)[3], 1.0f);
    QCOMPARE(im.pixel(2, 2)[3], 0.0f);
    const std::vector<int> w = rowWidths(im);
    QVERIFY(maxOf(w) > 200);  // framed with a small margin
  }

  void twistTurnsTopAndBottomLayersOppositeWays() {
    TwistParams tp;
    const PointCloud moved = applyCameras(cube_, {twistEffect(tp)});
    double turn[3] = {0, 0, 0};
    int count[3] = {0, 0, 0};
    for (size_t i = 0; i < cube_.size(); ++i) {
      const Eigen::Vector3d &a = cube_.positions[i], &b = moved.positions[i];
      const int layer = cubeOf(a).y();
      turn[layer] += std::remainder(std::atan2(b.z(), b.x()) - std::atan2(a.z(), a.x()), 2 * M_PI);
      ++count[layer];
    }
    for (double& t : turn) t = t / count[&t - turn];
    // Layer centres at heights -2/3, 0, 2/3: turns of about ∓atan(0.35·2/3) = ∓13°.
    QVERIFY2(std::abs(turn[2] - std::atan(tp.rate * 2 / 3)) < 0.02,
             qPrintable(QString::number(turn[2])));
    QVERIFY(std::abs(turn[1]) < 1e-9);
    QVERIFY(std::abs(turn[0] + turn[2]) < 1e-9);
    // Seen head-on, the turned top and bottom layers show wider than the unturned middle one,
    // where the original is a square.
    const Camera view = headOnOrthographic();
    const std::vector<int> before = rowWidths(renderCloud(cube_, {}, view, small()));
    const std::vector<int> after = rowWidths(renderCloud(cube_, {twistEffect(tp)}, view, small()));
    QVERIFY(std::abs(maxOf(before) - before[128]) <= 2);
    QVERIFY2(maxOf(after) > 1.15 * after[128],
             qPrintable(QString("%1 vs %2").arg(maxOf(after)).arg(after[128])));
  }

  void pincushionPullsCornersOutSoSidesCurveIn() {
    const Camera view = headOnOrthographic();
    const std::vector<int> before = rowWidths(renderCloud(cube_, {}, view, small()));
    const std::vector<int> after =
        rowWidths(renderCloud(cube_, {pincushionEffect({})}, view, small()));
    // Original: a square, as wide at its middle row as anywhere. Pin-cushion: corners stick out.
    QVERIFY(std::abs(maxOf(before) - before[128]) <= 2);
    QVERIFY2(maxOf(after) > 1.1 * after[128],
             qPrintable(QString("%1 vs %2").arg(maxOf(after)).arg(after[128])));
    // Barrel (k < 0) does the opposite: the middle row is the widest.
    const std::vector<int> barrel =
        rowWidths(renderCloud(cube_, {pincushionEffect({-0.12, {}})}, view, small()));
    QVERIFY(std::abs(maxOf(barrel) - barrel[128]) <= 2);
  }

  void inversePerspectiveRendersTheFarFaceLargerThanTheNear() {
    InversePerspectiveParams ip;
    ip.eye = {0, 0, -5};
    ip.target = {0, 0, 0};
    PinholeParams pin;
    pin.pose = headOn();
    const Camera view = pinholeCamera(pin);
    // Image widths of the near face (front faces of the front cubes) and the far face.
    const auto faceWidths = [&](const std::vector<Camera>& effects) {
      const PointCloud moved = applyCameras(cube_, effects);
      double near[2] = {1e9, -1e9}, far[2] = {1e9, -1e9};
      for (size_t i = 0; i < cube_.size(); ++i) {
        const double z = cube_.positions[i].z();
        if (std::abs(std::abs(z) - 0.96) > 0.01) continue;  // outer faces at ±(2/3 + side/2)
        const Eigen::Vector3d& m = moved.positions[i];
        const double u = view.evaluate(Eigen::Vector4d(m.x(), m.y(), m.z(), 1))[0];
        double* range = z < 0 ? near : far;
        range[0] = std::min(range[0], u);
        range[1] = std::max(range[1], u);
      }
      return std::pair{near[1] - near[0], far[1] - far[0]};
    };
    const auto [near0, far0] = faceWidths({});
    QVERIFY(far0 < 0.8 * near0);  // ordinary perspective
    const auto [near1, far1] = faceWidths({inversePerspectiveEffect(ip)});
    QVERIFY2(far1 > 1.25 * near1, qPrintable(QString("far %1 near %2").arg(far1).arg(near1)));
    // In the render the far (blue) cubes now show around the near face.
    const auto farPixels = [&](const std::vector<Camera>& effects) {
      const ImageF im = renderCloud(cube_, effects, view, small());
      int n = 0;
      for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
          n += im.pixel(x, y)[2] > 0.5f;  // only k = 2 cubes are so blue
      return n;
    };
    const int before = farPixels({}), after = farPixels({inversePerspectiveEffect(ip)});
    QVERIFY2(after > 5 * before + 1000, qPrintable(QString("%1 then %2").arg(before).arg(after)));
  }

  void warmColoursExpandAndColdOnesShrink() {
    const ColourScaleParams cs;
    const PointCloud moved = applyCameras(cube_, {colourScaleEffect(cs)});
    // The warmest cube (2, 1, 0) and the coldest (0, 1, 2): sizes from their moved points.
    const auto extent = [&](const Eigen::Vector3i& which) {
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
      for (size_t i = 0; i < cube_.size(); ++i)
        if (cubeOf(cube_.positions[i]) == which) {
          lo = lo.cwiseMin(moved.positions[i]);
          hi = hi.cwiseMax(moved.positions[i]);
        }
      return (hi - lo).x();
    };
    const Eigen::Vector4f warm = cubeOfCubesColour(2, 1, 0), cold = cubeOfCubesColour(0, 1, 2);
    const double expected =
        (1 + cs.strength * (warm[0] - warm[2])) / (1 + cs.strength * (cold[0] - cold[2]));
    const double measured = extent({2, 1, 0}) / extent({0, 1, 2});
    QVERIFY2(std::abs(measured - expected) < 0.02 * expected,
             qPrintable(QString("%1 vs %2").arg(measured).arg(expected)));
    QVERIFY(measured > 1.8);
    // Seen from above, the warm top corner cube covers more pixels than the cold one.
    OrthographicParams top;
    top.scale = 0.3;
    top.pose = CameraPose::lookAt({0, 5, 0}, {0, 0, 0}, {0, 0, 1});
    const ImageF im = renderCloud(cube_, {colourScaleEffect(cs)}, orthographicCamera(top), small());
    // Colours as stored in the file (uchar sRGB), which is what the render carries.
    const auto colourOf = [&](const Eigen::Vector3i& which) {
      for (size_t i = 0; i < cube_.size(); ++i)
        if (cubeOf(cube_.positions[i]) == which) return cube_.colours[i];
      return Eigen::Vector4f(Eigen::Vector4f::Zero());
    };
    const Eigen::Vector4f warm_top = colourOf({2, 2, 0}), cold_top = colourOf({0, 2, 2});
    int warm_px = 0, cold_px = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const Eigen::Map<const Eigen::Vector4f> c(im.pixel(x, y));
        warm_px += (c - warm_top).norm() < 1e-4f;
        cold_px += (c - cold_top).norm() < 1e-4f;
      }
    QVERIFY2(cold_px > 100 && warm_px > 2.5 * cold_px,
             qPrintable(QString("warm %1 cold %2").arg(warm_px).arg(cold_px)));
  }

  void chromaticAberrationSeparatesTheLayers() {
    // The paper's eq 8/9 per layer: a layer moves by s·(its channel), so the red-rich cubes' red
    // layer grows past their green and blue layers and leaves a pure red fringe.
    ChromaticAberrationParams ca;
    ca.red = 0.1;
    ca.blue = -0.1;
    CloudRenderOptions o = small();
    o.layers = RenderLayers::Rgb;
    const auto redFringe = [](const ImageF& im) {
      int n = 0;
      for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
          const float* c = im.pixel(x, y);
          n += c[0] > 0.5f && c[1] == 0.0f && c[2] == 0.0f;
        }
      return n;
    };
    const ImageF split =
        renderCloud(cube_, {chromaticAberrationEffect(ca)}, headOnOrthographic(), o);
    const int fringe = redFringe(split);
    // 0.1 × 37 px ≈ 3.7 px along the red cubes' outer edge (74 px tall).
    QVERIFY2(fringe > 150, qPrintable(QString::number(fringe)));
    // Whole points have all three channels (every cube has ≥ sRGB 0.15 of each): no fringe.
    QCOMPARE(redFringe(renderCloud(cube_, {}, headOnOrthographic(), small())), 0);
    // The layers stay registered where the cloud does not move them: the centre pixel.
    QCOMPARE(split.pixel(128, 128)[3], 1.0f);
  }
};

QTEST_GUILESS_MAIN(TestFig1)
#include "test_fig1.moc"
