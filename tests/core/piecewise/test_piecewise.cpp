// SPDX-License-Identifier: Apache-2.0
// Piecewise cameras against a ray-traced mirror sphere: exact matches from the
// tracer, the quadtree fit must bring every match under the threshold, the seams must agree,
// the mesh render of an inserted graphic must match the ray-traced image of it, and the
// .artcam round trip must keep every patch.
#include "core/io/atomic_file.h"
#include "core/io/artcam_file.h"
#include "core/piecewise/piecewise_fit.h"
#include "core/piecewise/piecewise_render.h"
#include "core/piecewise/sample_scenes.h"

#include <QtTest/QtTest>

#include <QTemporaryDir>

#include <cmath>
#include <cstdio>

using namespace artcam;
using artcam::MirrorSphereScene;
using artcam::WaterGlassScene;

namespace {

template <class Scene>
std::vector<PointMatch> tracedMatches(const Scene& scene, double step, double offset) {
  std::vector<PointMatch> out;
  for (double y = offset; y < scene.photo_height; y += step)
    for (double x = offset; x < scene.photo_width; x += step)
      if (const auto g = scene.graphicFromPhoto({x, y})) {
        PointMatch m;
        m.source = *g;
        m.target = Eigen::Vector2d(x, y);
        out.push_back(m);
      }
  return out;
}

// Smooth colours (periods of 60–110 graphic pixels) so PSNR measures geometry, not aliasing.
ImageF makeGraphic(int size) {
  ImageF g(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float* p = g.pixel(x, y);
      p[0] = static_cast<float>(0.5 + 0.4 * std::sin(x / 11.0));
      p[1] = static_cast<float>(0.5 + 0.4 * std::cos(y / 17.0));
      p[2] = static_cast<float>(0.5 + 0.4 * std::sin((x + y) / 15.0));
    }
  return g;
}

// Bilinear (centres at i + 0.5) with clamping: the reference sampler, written independently of
// the renderer's.
Eigen::Vector3d sampleReference(const ImageF& g, const Eigen::Vector2d& at) {
  const double fx = std::clamp(at.x() - 0.5, 0.0, g.width - 1.0);
  const double fy = std::clamp(at.y() - 0.5, 0.0, g.height - 1.0);
  const int x0 = std::min(static_cast<int>(fx), g.width - 2);
  const int y0 = std::min(static_cast<int>(fy), g.height - 2);
  const double tx = fx - x0, ty = fy - y0;
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c)
    out[c] = (1 - ty) * ((1 - tx) * g.pixel(x0, y0)[c] + tx * g.pixel(x0 + 1, y0)[c]) +
             ty * ((1 - tx) * g.pixel(x0, y0 + 1)[c] + tx * g.pixel(x0 + 1, y0 + 1)[c]);
  return out;
}

struct Comparison {
  double psnr_db = 0.0;
  double coverage = 0.0;  // share of interior reference pixels the render covers
  int pixels = 0;
};

template <class Scene>
Comparison compareWithTracer(const ImageF& rendered, const ImageF& graphic, const Scene& scene) {
  double se = 0.0;
  int n = 0, interior = 0, covered = 0;
  for (int y = 1; y + 1 < scene.photo_height; ++y)
    for (int x = 1; x + 1 < scene.photo_width; ++x) {
      bool all = true;  // the pixel and its neighbours all see the graphic: not a border pixel
      for (int dy = -1; dy <= 1 && all; ++dy)
        for (int dx = -1; dx <= 1 && all; ++dx)
          all = scene.graphicFromPhoto({x + dx + 0.5, y + dy + 0.5}).has_value();
      if (!all) continue;
      ++interior;
      const float* p = rendered.pixel(x, y);
      if (p[3] > 0.5f) ++covered;
      if (p[3] < 0.999f) continue;
      const Eigen::Vector3d truth = sampleReference(graphic, *scene.graphicFromPhoto({x + 0.5, y + 0.5}));
      for (int c = 0; c < 3; ++c) se += (p[c] / p[3] - truth[c]) * (p[c] / p[3] - truth[c]);
      n += 3;
    }
  Comparison out;
  out.pixels = n / 3;
  out.coverage = interior > 0 ? double(covered) / interior : 0.0;
  out.psnr_db = n > 0 ? 10.0 * std::log10(1.0 / (se / n)) : 0.0;
  return out;
}

}  // namespace

class TestPiecewise : public QObject {
  Q_OBJECT

  MirrorSphereScene scene_;
  FrameSize source_{512, 512};
  FrameSize target_{320, 240};

 private slots:
  void fitsTheMirrorSphereBelowTheThreshold() {
    const std::vector<PointMatch> matches = tracedMatches(scene_, 3.0, 0.5);
    QVERIFY(matches.size() > 500);
    PiecewiseOptions options;
    options.max_error_px = 0.25;
    const PiecewiseSummary fit = fitPiecewise(matches, source_, target_, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    std::printf("mirror sphere: %s\n", fit.report().c_str());
    // At the matches within the threshold; between them (held out) a few patches at the rim,
    // which cannot split further, stay a little above it, and say so.
    QVERIFY2(fit.max_px <= options.max_error_px, qPrintable(QString::number(fit.max_px)));
    QVERIFY2(fit.held_out_max_px <= 1.5 * options.max_error_px, fit.report().c_str());
    for (const CameraPatch& p : fit.camera.patches)
      QCOMPARE(p.within_tolerance, p.max_px <= options.max_error_px &&
                                       p.held_out_max_px <= options.max_error_px);
    QVERIFY(fit.camera.patches.size() > 1);
    // A single rational quadratic cannot do it (that is why the paper patches).
    QVERIFY(fit.single_max_px > 4 * options.max_error_px);
    QVERIFY2(fit.seam_gap_px < 2 * options.max_error_px, qPrintable(QString::number(fit.seam_gap_px)));

    // Held out: traced points between the fitting grid's.
    double worst = 0.0;
    for (const PointMatch& m : tracedMatches(scene_, 3.0, 2.0)) {
      const auto y = fit.camera.targetPixelFromSourcePixel(m.source);
      if (y) worst = std::max(worst, (*y - m.target).norm());
    }
    std::printf("mirror sphere: held-out max %.3f px\n", worst);
    QVERIFY(worst < 4 * options.max_error_px);
  }

  void insertedGraphicMatchesTheRayTracedOne() {
    PiecewiseOptions options;
    options.max_error_px = 0.25;
    const PiecewiseSummary fit = fitPiecewise(tracedMatches(scene_, 3.0, 0.5), source_, target_, options);
    QVERIFY(fit.status.ok);
    const ImageF graphic = makeGraphic(scene_.graphic_size);
    PiecewiseRenderStats stats;
    const ImageF rendered = renderPiecewise(graphic, fit.camera, {}, &stats);
    QCOMPARE(rendered.width, 320);
    QCOMPARE(rendered.alpha_channel, 3);
    for (float v : rendered.data) QVERIFY(std::isfinite(v));
    const Comparison c = compareWithTracer(rendered, graphic, scene_);
    std::printf("insertion vs ray tracing: PSNR %.1f dB over %d pixels, coverage %.4f, %d triangles\n",
                c.psnr_db, c.pixels, c.coverage, stats.triangles);
    QVERIFY(c.pixels > 2000);
    QVERIFY(c.coverage > 0.95);
    QVERIFY2(c.psnr_db > 35.0, qPrintable(QString::number(c.psnr_db)));

    // The single camera, rendered the same way, is visibly worse: the comparison means something.
    FitOptions fo;
    fo.model = ModelClass::Quadratic;
    fo.require_pole_free = false;
    fo.diagnostics = false;
    const FitSummary single = fitImageCamera(tracedMatches(scene_, 3.0, 0.5), source_, target_, fo);
    QVERIFY(single.status.ok);
    PiecewiseCamera one{source_, target_, {fit.camera.patches.front()}};
    one.patches.front().camera = single.camera;
    one.patches.front().rect = {0, 0, 512, 512};
    const Comparison s = compareWithTracer(renderPiecewise(graphic, one), graphic, scene_);
    std::printf("single camera vs ray tracing: PSNR %.1f dB\n", s.psnr_db);
    QVERIFY(s.psnr_db < c.psnr_db - 6.0);
  }

  void refractsThroughAGlassOfWater() {
    const WaterGlassScene glass;
    const std::vector<PointMatch> matches = tracedMatches(glass, 3.0, 0.5);
    QVERIFY(matches.size() > 500);
    PiecewiseOptions options;
    options.max_error_px = 0.25;
    const PiecewiseSummary fit = fitPiecewise(matches, source_, target_, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    std::printf("glass of water: %s\n", fit.report().c_str());
    QVERIFY(fit.converged);
    QVERIFY(fit.max_px <= options.max_error_px);
    QVERIFY(fit.single_max_px > 4 * options.max_error_px);
    const ImageF graphic = makeGraphic(glass.graphic_size);
    const Comparison c = compareWithTracer(renderPiecewise(graphic, fit.camera), graphic, glass);
    std::printf("glass of water insertion vs ray tracing: PSNR %.1f dB over %d pixels, coverage %.4f\n",
                c.psnr_db, c.pixels, c.coverage);
    QVERIFY(c.pixels > 2000);
    // The support is the matches' hull grown by one match spacing: interior pixels within
    // about a grid step of the region's true edge stay uncovered.
    QVERIFY(c.coverage > 0.95);
    QVERIFY2(c.psnr_db > 35.0, qPrintable(QString::number(c.psnr_db)));
  }

  // Fig 8 whole: one glass seen through air above the waterline and through water below it,
  // each region fitted piecewise to its own traced matches, each insertion against the ray
  // tracer; the water bends more, so it needs more patches than the air.
  void refractsThroughAirAndWaterInOneGlass() {
    int patches[2] = {0, 0};
    for (const auto medium :
         {artcam::GlassOfWaterScene::Medium::Air, artcam::GlassOfWaterScene::Medium::Water}) {
      artcam::GlassOfWaterScene glass;
      glass.medium = medium;
      const bool water = medium == artcam::GlassOfWaterScene::Medium::Water;
      const std::vector<PointMatch> matches = tracedMatches(glass, 3.0, 0.5);
      QVERIFY2(matches.size() > 300, qPrintable(QString::number(matches.size())));
      PiecewiseOptions options;
      options.max_error_px = 0.25;
      const PiecewiseSummary fit = fitPiecewise(matches, source_, target_, options);
      QVERIFY2(fit.status.ok, fit.status.message.c_str());
      std::printf("glass, through %s: %s\n", water ? "water" : "air", fit.report().c_str());
      QVERIFY(fit.converged);
      QVERIFY(fit.max_px <= options.max_error_px);
      patches[water ? 1 : 0] = static_cast<int>(fit.camera.patches.size());
      const ImageF graphic = makeGraphic(glass.graphic_size);
      const Comparison c = compareWithTracer(renderPiecewise(graphic, fit.camera), graphic, glass);
      std::printf("glass through %s vs ray tracing: PSNR %.1f dB over %d pixels, coverage %.4f\n",
                  water ? "water" : "air", c.psnr_db, c.pixels, c.coverage);
      QVERIFY(c.pixels > 1000);
      QVERIFY(c.coverage > 0.95);
      QVERIFY2(c.psnr_db > 35.0, qPrintable(QString::number(c.psnr_db)));
    }
    QVERIFY2(patches[1] > patches[0],
             qPrintable(QString("air %1, water %2").arg(patches[0]).arg(patches[1])));
  }

  void fitsAFisheyeBeyondOneQuadratic() {
    // Equidistant fisheye: a rectilinear pixel at radius r from the centre lands at
    // f·atan(r / f) (a 140° diagonal field on 640×480): stronger than one rational quadratic.
    const double f = 200.0;
    std::vector<PointMatch> matches;
    for (double y = 4; y < 480; y += 16)
      for (double x = 4; x < 640; x += 16) {
        const Eigen::Vector2d d(x - 320.0, y - 240.0);
        const double r = d.norm();
        const double scale = r > 0 ? f * std::atan(r / f) / r : 1.0;
        PointMatch m;
        m.source = Eigen::Vector2d(x, y);
        m.target = Eigen::Vector2d(320.0, 240.0) + scale * d;
        matches.push_back(m);
      }
    PiecewiseOptions options;
    options.max_error_px = 0.1;
    const PiecewiseSummary fit = fitPiecewise(matches, {640, 480}, {640, 480}, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    std::printf("fisheye: %s\n", fit.report().c_str());
    QVERIFY(fit.converged);
    QVERIFY(fit.max_px <= options.max_error_px);
    QVERIFY(fit.single_max_px > 10 * options.max_error_px);
  }

  // A map sampled at pixel centres on a grid (as `fit --stmap` samples one) stops short of the
  // frame's edges by up to a step; the outer patches still reach them, so every source pixel
  // along the frame is mapped (issue 44: a transparent ring up to a step deep otherwise).
  void outerPatchesReachTheFrame() {
    const FrameSize frame{640, 480};
    std::vector<PointMatch> matches;
    for (double y = 4; y < 480; y += 16)
      for (double x = 4; x < 640; x += 16) {  // the last column at 628, the last row at 468
        const Eigen::Vector2d d(x - 320.0, y - 240.0);
        const double r = d.norm();
        PointMatch m;
        m.source = Eigen::Vector2d(x, y);
        m.target = Eigen::Vector2d(320.0, 240.0) + (r > 0 ? 200.0 * std::atan(r / 200.0) / r : 1.0) * d;
        matches.push_back(m);
      }
    const PiecewiseSummary fit = fitPiecewise(matches, frame, frame, {});
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    int unmapped = 0;
    for (double t = 0.5; t < 640; t += 1.0)
      for (const Eigen::Vector2d& p : {Eigen::Vector2d(t, 0.5), Eigen::Vector2d(t, 479.5)})
        unmapped += fit.camera.targetPixelFromSourcePixel(p) ? 0 : 1;
    for (double t = 0.5; t < 480; t += 1.0)
      for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.5, t), Eigen::Vector2d(639.5, t)})
        unmapped += fit.camera.targetPixelFromSourcePixel(p) ? 0 : 1;
    QCOMPARE(unmapped, 0);
    for (const CameraPatch& p : fit.camera.patches)  // and never past the frame
      QVERIFY(p.rect.x0 >= 0 && p.rect.y0 >= 0 && p.rect.x1 <= 640 && p.rect.y1 <= 480);
  }

  // Patches tile the source frame: a match outside it is refused before anything is fitted,
  // naming it, instead of a camera that cannot be written (issue 44).
  void matchesOutsideTheFrameAreRefusedBeforeFitting() {
    std::vector<PointMatch> matches = tracedMatches(scene_, 8.0, 0.5);
    PointMatch outside = matches.front();
    outside.source = Eigen::Vector2d(source_.width + 40.0, 10.0);
    matches.push_back(outside);
    const PiecewiseSummary fit = fitPiecewise(matches, source_, target_, {});
    QVERIFY(!fit.status.ok);
    const std::string expected = "match " + std::to_string(matches.size()) +
                                 ": its source (552, 10) lies outside the 512x512 source frame";
    QVERIFY2(fit.status.message.find(expected) != std::string::npos, fit.status.message.c_str());
  }

  void compositeOverKeepsThePhotoWhereTheGraphicIsAbsent() {
    ImageF photo(4, 1, 3);
    for (float& v : photo.data) v = 0.25f;
    ImageF top(4, 1, 4, 3);
    top.pixel(1, 0)[0] = 0.5f, top.pixel(1, 0)[3] = 0.5f;  // half-covered red, premultiplied
    top.pixel(2, 0)[1] = 1.0f, top.pixel(2, 0)[3] = 1.0f;  // opaque green
    compositeOver(top, photo);
    QCOMPARE(photo.pixel(0, 0)[0], 0.25f);
    QCOMPARE(photo.pixel(1, 0)[0], 0.5f + 0.5f * 0.25f);
    QCOMPARE(photo.pixel(1, 0)[1], 0.5f * 0.25f);
    QCOMPARE(photo.pixel(2, 0)[1], 1.0f);
    QCOMPARE(photo.pixel(2, 0)[0], 0.0f);
  }

  void fileRoundTripKeepsEveryPatch() {
    PiecewiseOptions options;
    options.max_error_px = 0.5;
    const std::vector<PointMatch> matches = tracedMatches(scene_, 4.0, 0.5);
    const PiecewiseSummary fit = fitPiecewise(matches, source_, target_, options);
    QVERIFY(fit.status.ok);
    QTemporaryDir dir;
    const std::string path = dir.filePath("sphere.artcam").toStdString();
    Artcam doc(fit.camera.patches.front().camera);
    doc.pieces = fit.camera;
    QVERIFY(writeArtcam(path, doc).ok);
    const auto back = readArtcam(path);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(back->pieces.has_value());
    QCOMPARE(back->pieces->patches.size(), fit.camera.patches.size());
    QCOMPARE(back->pieces->support_margin_px, fit.camera.support_margin_px);
    // Everywhere, not only at the matches: the supports must survive too.
    for (int k = 0; k < 2000; ++k) {
      const Eigen::Vector2d q(512.0 * (k % 50) / 49.0, 512.0 * (k / 50) / 39.0);
      const auto a = fit.camera.targetPixelFromSourcePixel(q);
      const auto b = back->pieces->targetPixelFromSourcePixel(q);
      QCOMPARE(a.has_value(), b.has_value());
      if (a) QCOMPARE((*a - *b).norm(), 0.0);  // bit-exact numbers in the file
    }
    // A plain reader still opens it (the top-level single camera).
    QVERIFY(readArtcam(path).ok());
  }

  void badPatchesAreNamed() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("bad.artcam").toStdString();
    const Camera c = Camera::identity({{BlockKind::Position, 3}}, {64, 64}, {64, 64});
    std::string text = toArtcamJson(Artcam(c));
    text.insert(text.rfind('}'), ", \"patches\": [ {\"rect\": [10, 0, 5, 8]} ]");
    QVERIFY(writeTextAtomically(path, text).ok);
    const auto back = readArtcam(path);
    QVERIFY(!back.ok());
    QVERIFY2(back.status.message.find("/patches/0/rect") != std::string::npos,
             back.status.message.c_str());
  }

  void tooFewMatchesIsAClearError() {
    std::vector<PointMatch> few = tracedMatches(scene_, 40.0, 0.5);
    few.resize(std::min<size_t>(few.size(), 5));
    const PiecewiseSummary fit = fitPiecewise(few, source_, target_, {});
    QVERIFY(!fit.status.ok);
    QVERIFY(fit.status.message.find("at least") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestPiecewise)
#include "test_piecewise.moc"
