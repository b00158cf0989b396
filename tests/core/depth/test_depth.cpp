// SPDX-License-Identifier: Apache-2.0
// core/depth: painted regions, planes in inverse depth from three points, the depth raster and
// depth map files. Plane depths are checked against a closed form made here: a world plane seen
// by a pinhole, intersected with the ray through each pixel centre.
#include "core/io/depth_file.h"
#include "core/depth/depth_raster.h"
#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "core/io/image_io.h"
#include "tests/support/test_support.h"

#include <OpenImageIO/imageio.h>

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>

using namespace artcam;

namespace {

// A pinhole with focal f (px) and principal point (cx, cy) looking at the world plane n·X = d.
struct PlaneScene {
  double f = 700.0, cx = 160.0, cy = 120.0;
  Eigen::Vector3d n{0.1, -0.6, 0.8};
  double d = 5.0;

  // Depth z of the plane point seen through pixel position (x, y): X = z·((x−cx)/f, (y−cy)/f, 1).
  double depthAt(double x, double y) const {
    const Eigen::Vector3d ray((x - cx) / f, (y - cy) / f, 1.0);
    return d / n.dot(ray);
  }
};

bool noNaN(const ImageF& img) {
  for (float v : img.data)
    if (!std::isfinite(v)) return false;
  return true;
}

RegionMask fullMask(int w, int h) {
  RegionMask m(w, h);
  m.fillPolygon({{-1, -1}, {w + 1.0, -1}, {w + 1.0, h + 1.0}, {-1, h + 1.0}});
  return m;
}

}  // namespace

class TestDepth : public QObject {
  Q_OBJECT

 private slots:
  void aMapOfAnotherAspectIsSaidToStretch() {
    // A map at the photo's aspect, at any resolution, is sampled as it is (a sensor's depth is
    // often a quarter of the photo's side); another shape is stretched, and the note names both.
    QCOMPARE(depthMapAspectNote({600, 400}, {600, 400}), std::string());
    QCOMPARE(depthMapAspectNote({150, 100}, {600, 400}), std::string());
    QCOMPARE(depthMapAspectNote({767, 511}, {6000, 4000}), std::string());  // rounded
    QCOMPARE(depthMapAspectNote({80, 20}, {600, 400}),
             std::string("the depth map is 80x20 but the photo is 600x400 (another aspect): "
                         "depth is stretched per axis"));
    QVERIFY(!depthMapAspectNote({400, 600}, {600, 400}).empty());     // turned
    QCOMPARE(depthMapAspectNote({0, 0}, {600, 400}), std::string());  // no map
  }

  void planeFromThreePointsMatchesAPinholePlane() {
    const PlaneScene scene;
    std::array<DepthAnchor, 3> anchors;
    const Eigen::Vector2d at[3] = {{30.5, 200.25}, {290.0, 180.0}, {150.75, 20.0}};
    for (int i = 0; i < 3; ++i)
      anchors[static_cast<size_t>(i)] = {at[i], scene.depthAt(at[i].x(), at[i].y())};
    const Result<InverseDepthPlane> plane = planeFromAnchors(anchors);
    QVERIFY2(plane.ok(), plane.status.message.c_str());

    const int w = 320, h = 240;
    const RegionMask full = fullMask(w, h);
    std::vector<DepthLayer> layers{{&full, *plane}};
    DepthRasterSummary summary;
    const ImageF depth = rasteriseDepth(layers, w, h, nullptr, {}, &summary);
    QCOMPARE(depth.channels, 2);
    QCOMPARE(summary.covered, size_t{w * h});
    QCOMPARE(summary.clamped, size_t{0});
    // The plane is exact where its depth lies within its points' span, and holds the span's
    // end beyond it (inverse_depth_plane.h): the pinhole plane clamped to [near, far].
    const auto [near, far] = std::minmax({anchors[0].depth, anchors[1].depth, anchors[2].depth});
    const auto bounded = [&, near = near, far = far](double x, double y) {
      return std::clamp(scene.depthAt(x, y), near, far);
    };
    double worst = 0.0;
    int within = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const auto z = depthAt(depth, x, y);
        QVERIFY(z);
        const double truth = bounded(x + 0.5, y + 0.5);
        within += truth > near && truth < far;
        worst = std::max(worst, std::abs(*z - truth) / truth);
      }
    QVERIFY2(worst < 1e-6, qPrintable(QString("relative depth error %1").arg(worst)));
    QVERIFY2(within > w * h / 2, qPrintable(QString("%1 pixels within the span").arg(within)));

    // A reduced raster (the overlay) samples the same plane at its pixel centres' photo positions.
    DepthRasterOptions small;
    small.width = 80;
    small.height = 60;
    const ImageF reduced = rasteriseDepth(layers, w, h, nullptr, small);
    for (int y = 0; y < 60; y += 7)
      for (int x = 0; x < 80; x += 7) {
        const double truth = bounded((x + 0.5) * 4.0, (y + 0.5) * 4.0);
        QVERIFY(std::abs(*depthAt(reduced, x, y) - truth) / truth < 1e-6);
      }
  }

  void degenerateAnchorsAreRefused() {
    std::array<DepthAnchor, 3> line{DepthAnchor{{0, 0}, 1}, DepthAnchor{{10, 10}, 2},
                                    DepthAnchor{{20, 20.000001}, 3}};
    Result<InverseDepthPlane> r = planeFromAnchors(line);
    QVERIFY(!r.ok());
    QVERIFY(r.status.message.find("one line") != std::string::npos);
    std::array<DepthAnchor, 3> negative{DepthAnchor{{0, 0}, 1}, DepthAnchor{{10, 0}, -2},
                                        DepthAnchor{{0, 10}, 3}};
    r = planeFromAnchors(negative);
    QVERIFY(!r.ok());
    QVERIFY(r.status.message.find("depth point 2") != std::string::npos);
    std::array<DepthAnchor, 3> nan{DepthAnchor{{0, 0}, 1}, DepthAnchor{{10, 0}, 2},
                                   DepthAnchor{{0, std::nan("")}, 3}};
    QVERIFY(!planeFromAnchors(nan).ok());
  }

  void unpaintedPixelsHaveNoDepthAndNoNaN() {
    const int w = 64, h = 48;
    RegionMask mask(w, h);
    mask.fillPolygon({{8, 8}, {40, 8}, {40, 30}, {8, 30}});
    // A plane whose inverse depth crosses zero inside the region: clamped, never NaN or inf.
    InverseDepthPlane plane{0.01, 0.0, -0.2};  // 1/z = 0.01x − 0.2: ≤ 0 left of x = 20
    const RegionMask none(w, h);
    std::vector<DepthLayer> layers{{&mask, plane}, {&none, std::nullopt}};
    DepthRasterOptions options;
    options.max_depth = 500.0;
    DepthRasterSummary summary;
    const ImageF depth = rasteriseDepth(layers, w, h, nullptr, options, &summary);
    QVERIFY(noNaN(depth));
    QCOMPARE(summary.covered, size_t{32 * 22});
    QCOMPARE(summary.clamped, size_t{12 * 22});  // centres 8.5 … 19.5
    QCOMPARE(summary.max_depth, 500.0);
    QCOMPARE(depthAt(depth, 5, 5), std::optional<double>());
    QCOMPARE(depth.pixel(5, 5)[0], 0.0f);
    QCOMPARE(depth.pixel(5, 5)[1], 0.0f);
    QVERIFY(std::abs(*depthAt(depth, 30, 10) - 1.0 / (0.01 * 30.5 - 0.2)) < 1e-4);
  }

  void layersCompositeOverInInverseDepth() {
    const int w = 16, h = 8;
    RegionMask half(w, h);
    half.stamp({8, -16}, BrushOptions{30.0, 0.0, false});  // a soft rim: partial coverage on row 3
    const RegionMask full = fullMask(w, h);
    std::vector<DepthLayer> layers{{&full, InverseDepthPlane{0, 0, 1.0 / 2.0}},
                                   {&half, InverseDepthPlane{0, 0, 1.0 / 8.0}}};
    const ImageF depth = rasteriseDepth(layers, w, h);
    for (int x = 0; x < w; ++x) {
      const double a = half.at(x, 3) / 255.0;
      QVERIFY(a > 0.0 && a < 1.0);
      const double truth = 1.0 / (a / 8.0 + (1.0 - a) / 2.0);
      QVERIFY(std::abs(*depthAt(depth, x, 3) - truth) < 1e-5 * truth);
      QCOMPARE(depth.pixel(x, 3)[1], 1.0f);  // the bottom layer covers everything
    }
    // A fully covered top layer hides what is below.
    layers[1].mask = &full;
    QVERIFY(std::abs(*depthAt(rasteriseDepth(layers, w, h), 3, 3) - 8.0) < 1e-5);
  }

  void polygonCoversPixelCentresInside() {
    RegionMask m(48, 40);
    const PixelRect touched = m.fillPolygon({{10.2, 5.7}, {30.6, 5.7}, {30.6, 20.4}, {10.2, 20.4}});
    QVERIFY(!touched.empty());
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 48; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const bool inside = px >= 10.2 && px < 30.6 && py >= 5.7 && py < 20.4;
        QCOMPARE(m.at(x, y), static_cast<uint8_t>(inside ? 255 : 0));
      }
    QCOMPARE(m.coveredCount(), size_t{21 * 14});
    // A triangle against a barycentric inside test; then erase part of it with a polygon.
    RegionMask t(48, 40);
    const Eigen::Vector2d a(3, 35), b(44, 30), c(20, 2.5);
    t.fillPolygon({a, b, c});
    auto cross = [](Eigen::Vector2d p, Eigen::Vector2d q, Eigen::Vector2d r) {
      return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    };
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 48; ++x) {
        const Eigen::Vector2d p(x + 0.5, y + 0.5);
        const double s1 = cross(a, b, p), s2 = cross(b, c, p), s3 = cross(c, a, p);
        const bool inside = (s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0);
        QCOMPARE(t.at(x, y) == 255, inside);
      }
    t.fillPolygon({{0, 0}, {48, 0}, {48, 20}, {0, 20}}, /*erase=*/true);
    for (int x = 0; x < 48; ++x) QCOMPARE(t.at(x, 10), uint8_t{0});
  }

  void brushDabsHardSoftAndErase() {
    RegionMask m(64, 64);
    const Eigen::Vector2d centre(30.3, 25.8);
    m.stamp(centre, BrushOptions{9.0, 1.0, false});
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const double d = std::hypot(x + 0.5 - centre.x(), y + 0.5 - centre.y());
        QCOMPARE(m.at(x, y) == 255, d <= 9.0);
        QCOMPARE(m.at(x, y) == 0, d > 9.0);
      }
    RegionMask soft(64, 64);
    soft.stamp({32, 32}, BrushOptions{20.0, 0.25, false});
    QCOMPARE(soft.at(31, 31), uint8_t{255});          // within the hard core (5 px)
    QVERIFY(soft.at(31 + 12, 31) > 0 && soft.at(31 + 12, 31) < 255);
    QVERIFY(soft.at(31 + 10, 31) >= soft.at(31 + 15, 31));  // falls off outwards
    QCOMPARE(soft.at(31 + 21, 31), uint8_t{0});
    // A stroke is continuous (no gaps between dabs) and erasing clears its hard core.
    RegionMask stroke(64, 64);
    stroke.stamp({5, 32}, BrushOptions{3.0, 1.0, false});
    stroke.segment({5, 32}, {60, 32}, BrushOptions{3.0, 1.0, false});
    for (int x = 5; x < 60; ++x) QCOMPARE(stroke.at(x, 31), uint8_t{255});
    const PixelRect r = stroke.segment({20, 32}, {40, 32}, BrushOptions{5.0, 1.0, true});
    QVERIFY(r.x0 <= 15 && r.x1 >= 45);
    for (int x = 20; x < 40; ++x) QCOMPARE(stroke.at(x, 31), uint8_t{0});
    QCOMPARE(stroke.at(10, 31), uint8_t{255});
  }

  void rectCopyPasteRestores() {
    RegionMask m(32, 32);
    m.stamp({16, 16}, BrushOptions{6.0, 0.5, false});
    const RegionMask before = m;
    const PixelRect r{8, 9, 26, 20};
    const std::vector<uint8_t> saved = m.copyRect(r);
    m.fillPolygon({{0, 0}, {32, 0}, {32, 32}}, false);
    QVERIFY(!(m == before));
    m.fillPolygon({{0, 0}, {32, 0}, {32, 32}, {0, 32}}, true);
    m.pasteRect(r, saved);
    RegionMask expected(32, 32);
    expected.pasteRect(r, saved);
    QVERIFY(m == expected);
  }

  void runEncodingRoundTripsAndRefusesBadRuns() {
    for (int round = 0; round < 20; ++round) {
      const int w = 1 + static_cast<int>(test::uniform(0, 90)), h = 1 + static_cast<int>(test::uniform(0, 70));
      RegionMask m(w, h);
      for (int k = 0; k < 4; ++k)
        m.stamp({test::uniform(0, w), test::uniform(0, h)},
                BrushOptions{test::uniform(1, 20), test::uniform(0, 1), k == 3});
      const std::vector<uint8_t> bytes = encodeMaskRuns(m);
      const Result<RegionMask> back = decodeMaskRuns(bytes, w, h, "p.artcamproj: /depth/layers/0");
      QVERIFY(back.ok());
      QVERIFY(*back == m);
    }
    RegionMask m(10, 10);
    m.stamp({5, 5}, BrushOptions{3, 1, false});
    std::vector<uint8_t> bytes = encodeMaskRuns(m);
    QVERIFY(!decodeMaskRuns(bytes, 10, 11, "x").ok());  // runs short of the size
    QVERIFY(!decodeMaskRuns(bytes, 9, 10, "x").ok());   // runs beyond it
    bytes.pop_back();
    const Result<RegionMask> cut = decodeMaskRuns(bytes, 10, 10, "p: /depth/layers/0/mask");
    QVERIFY(!cut.ok());
    QVERIFY(cut.status.message.find("p: /depth/layers/0/mask") == 0);
  }

  void depthMapFiles() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    // A 16-bit PNG written through OpenImageIO with exact stored integers: depth in
    // millimetres; 0 = no depth.
    const std::string png = dir.filePath("depth.png").toStdString();
    {
      const uint16_t v[6] = {0, 1000, 2500, 65535, 1, 40000};
      auto out = OIIO::ImageOutput::create(png);
      QVERIFY(out);
      QVERIFY(out->open(png, OIIO::ImageSpec(3, 2, 1, OIIO::TypeDesc::UINT16)));
      QVERIFY(out->write_image(OIIO::TypeDesc::UINT16, v));
      QVERIFY(out->close());
    }
    DepthFileOptions mm;
    mm.scale = 0.001;
    DepthFileSummary info;
    const Result<ImageF> map = readDepthFile(png, mm, &info);
    QVERIFY2(map.ok(), map.status.message.c_str());
    QCOMPARE(info.pixel_type, std::string("uint16"));
    QCOMPARE(info.holes, 1LL);
    QCOMPARE(depthAt(*map, 0, 0), std::optional<double>());
    QVERIFY(std::abs(*depthAt(*map, 1, 0) - 1.0) < 1e-6);
    QVERIFY(std::abs(*depthAt(*map, 0, 1) - 65.535) < 1e-4);
    QVERIFY(std::abs(*depthAt(*map, 2, 1) - 40.0) < 1e-5);

    // Float EXR: values are depth; NaN and negatives have none.
    ImageF f(4, 1, 1);
    f.data = {2.5f, std::nanf(""), -1.0f, 1e3f};
    const std::string exr = dir.filePath("depth.exr").toStdString();
    WriteImageOptions as_float;
    as_float.pixel_type = "float";
    QVERIFY(writeImage(exr, f, nullptr, as_float).ok);
    const Result<ImageF> fmap = readDepthFile(exr, {}, &info);
    QVERIFY2(fmap.ok(), fmap.status.message.c_str());
    QCOMPARE(info.holes, 2LL);
    QCOMPARE(*depthAt(*fmap, 0, 0), 2.5);
    QCOMPARE(*depthAt(*fmap, 3, 0), 1000.0);
    QVERIFY(noNaN(*fmap));
    DepthFileOptions inverse;
    inverse.inverse = true;
    QVERIFY(std::abs(*depthAt(*readDepthFile(exr, inverse), 0, 0) - 0.4) < 1e-7);

    // As a base map under a layer: the layer covers its region, the map shows elsewhere.
    RegionMask left(4, 1);
    left.fillPolygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    const ImageF combined =
        rasteriseDepth({{&left, InverseDepthPlane{0, 0, 0.1}}}, 4, 1, &*fmap);
    QVERIFY(std::abs(*depthAt(combined, 0, 0) - 10.0) < 1e-5);
    QCOMPARE(depthAt(combined, 1, 0), std::optional<double>());
    QVERIFY(std::abs(*depthAt(combined, 3, 0) - 1000.0) < 1e-2);

    const Result<ImageF> missing = readDepthFile(dir.filePath("nope.exr").toStdString());
    QVERIFY(!missing.ok());
    QVERIFY(missing.status.message.find("nope.exr") != std::string::npos);
    QVERIFY(missing.status.message.find("no such file") != std::string::npos);
    DepthFileOptions bad;
    bad.scale = 0.0;
    QVERIFY(readDepthFile(exr, bad).status.message.find("scale") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestDepth)
#include "test_depth.moc"
