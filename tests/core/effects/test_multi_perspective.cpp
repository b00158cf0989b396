// SPDX-License-Identifier: Apache-2.0
// Push-broom, crossed-slits and general linear cameras applied to a photo with depth
// (core/effects/multi_perspective.h), against ray geometry and never against their tensors:
// - each photo pixel (u, v) with depth d is back-projected through the photo's pinhole to
//   P = (u·d/f, v·d/f, d), and the image point whose ray passes through P is found from the
//   rays alone (glcRay, pushbroomRay, xslitRay: written from the geometry, glc.h and
//   projective_cameras.h), then compared with where the camera maps (u, v | colour | d);
// - the GLC that is the photo's own pinhole returns every pixel where it was;
// - a render through the front door puts the photo's pixels where the rays say.
#include "core/cameras/glc.h"
#include "core/cameras/projective_cameras.h"
#include "core/effects/effect_table.h"
#include "core/effects/multi_perspective.h"
#include "core/model/artcam.h"
#include "core/model/frames.h"
#include "core/pipeline/render.h"
#include "core/render/attributed.h"

#include <Eigen/Dense>
#include <QtTest/QtTest>

#include <cmath>
#include <functional>
#include <numbers>

using namespace artcam;

namespace {

constexpr double kPositionTolerance = 1e-6;  // normalised units
const FrameSize kFrame{64, 48};

// A tilted plane's depth over the photo: in [2, 8] on the frame.
double planeDepth(const Eigen::Vector2d& p) { return 5.0 + 2.0 * p.x() - 1.5 * p.y(); }

Eigen::Vector3d backProject(const Eigen::Vector2d& p, double d, double focal) {
  return {p.x() * d / focal, p.y() * d / focal, d};
}

// The camera applied to one pixel: x = [(u, v, 1) | rgba | (d, 1)] (eq 4), divided (eq 5).
struct Mapped {
  Eigen::Vector2d position;
  Eigen::Vector4d rgba;
  double depth;
};
Mapped apply(const Camera& camera, const Eigen::Vector2d& p, double d) {
  Eigen::VectorXd x(9);
  x << p.x(), p.y(), 1.0, 0.2, 0.3, 0.4, 1.0, d, 1.0;
  const Eigen::VectorXd y = camera.evaluate(x);
  return {y.head<2>(), y.segment<4>(3), y[7]};
}

// The pixel centres of the frame, every third, as normalised points.
std::vector<Eigen::Vector2d> samplePoints() {
  std::vector<Eigen::Vector2d> points;
  for (int j = 0; j < kFrame.height; j += 3)
    for (int i = 0; i < kFrame.width; i += 3)
      points.push_back(normalizedFromPixel(kFrame, {i + 0.5, j + 0.5}));
  return points;
}

// The image point whose GLC ray passes through P, from glcRay alone: the ray of q crosses the
// plane z = P.z at a point that is affine in q (its origin and direction are), so three rays
// give that affine map and one solve inverts it.
Eigen::Vector2d glcImageOf(const GlcParams& glc, const Eigen::Vector3d& p) {
  const auto crossing = [&](const Eigen::Vector2d& q) {
    const Ray ray = glcRay(glc, q);
    return Eigen::Vector2d(
        (ray.origin + (p.z() - ray.origin.z()) / ray.direction.z() * ray.direction).head<2>());
  };
  const Eigen::Vector2d c0 = crossing({0, 0});
  Eigen::Matrix2d a;
  a.col(0) = crossing({1, 0}) - c0;
  a.col(1) = crossing({0, 1}) - c0;
  return a.fullPivLu().solve(p.head<2>() - c0);
}

// A GLC that is none of the named ones: three generators from scattered origins, their
// directions near the pinhole's of focal 1.6.
GlcParams scatteredGlc() {
  GlcParams glc;
  const Eigen::Vector2d images[3] = {{-0.5, -0.4}, {0.6, -0.2}, {0.1, 0.5}};
  const Eigen::Vector2d origins[3] = {{0.2, -0.1}, {-0.15, 0.05}, {0.05, 0.25}};
  const Eigen::Vector2d bends[3] = {{0.03, 0.0}, {-0.02, 0.04}, {0.0, -0.03}};
  for (int i = 0; i < 3; ++i)
    glc.rays[static_cast<size_t>(i)] = {origins[i], origins[i] + images[i] / 1.6 + bends[i],
                                        images[i]};
  return glc;
}

}  // namespace

class TestMultiPerspective : public QObject {
  Q_OBJECT

 private slots:
  // Every sampled pixel of a tilted plane lands where the GLC's ray through its 3D point shows,
  // for a scattered GLC and for the three presets' GLCs stated with a focal other than 1.
  void pixelsLandWhereTheRaysThroughTheirPointsShow() {
    const double focal = 1.7;
    const std::vector<std::pair<const char*, GlcParams>> glcs = {
        {"scattered", scatteredGlc()},
        {"push-broom", photoPushbroomGlc({2.5, 25.0}, focal)},
        {"crossed slits", photoXSlitGlc({1.0, 4.0, 3.5}, focal)},
        {"parallax", photoParallaxGlc({{0.1, -0.05}, {0.2, 0.3}, {-0.3, 0.1}}, focal)}};
    for (const auto& [name, glc] : glcs) {
      const Camera camera = photoGlcCamera(glc, focal, kFrame);
      QCOMPARE(camera.stages().size(), size_t{2});
      double worst = 0.0;
      for (const Eigen::Vector2d& p : samplePoints()) {
        const double d = planeDepth(p);
        const Eigen::Vector3d point = backProject(p, d, focal);
        const Eigen::Vector2d want = glcImageOf(glc, point);
        QVERIFY2(glcRay(glc, want).distanceTo(point) < 1e-9, name);  // the solve is exact
        const Mapped got = apply(camera, p, d);
        worst = std::max(worst, (got.position - want).norm());
        // Colour passes unchanged; the depth output is the input depth.
        QVERIFY2((got.rgba - Eigen::Vector4d(0.2, 0.3, 0.4, 1.0)).norm() < 1e-12, name);
        QVERIFY2(std::abs(got.depth - d) < 1e-12 * d, name);
      }
      QVERIFY2(worst < kPositionTolerance,
               qPrintable(QString("%1: off by %2").arg(name).arg(worst)));
    }
  }

  // The presets against the named cameras' own rays (projective_cameras.h) and the header's
  // closed forms, at defaults and other settings; the photo's focal cancels.
  void presetsAgainstTheNamedCamerasRays() {
    const double focal = 1.3;
    for (const double dr : {3.0, 0.7}) {
      const Camera camera = photoPushbroomCamera({dr, 0.0}, kFrame);
      // The push-broom of focal f across and scale f/d_r along the sweep.
      PushbroomParams pb;
      pb.focal = focal;
      pb.scale = focal / dr;
      for (const Eigen::Vector2d& p : samplePoints()) {
        const double d = planeDepth(p);
        const Eigen::Vector3d point = backProject(p, d, focal);
        const Eigen::Vector2d want(p.x() * d / dr, p.y());
        QVERIFY(pushbroomRay(pb, want).distanceTo(point) < 1e-9);
        QVERIFY((apply(camera, p, d).position - want).norm() < kPositionTolerance);
      }
    }
    // A sweep turned by θ: the push-broom in the frame turned by θ (a along the sweep).
    const double theta = 35.0 * std::numbers::pi / 180.0;
    const Eigen::Vector2d a(std::cos(theta), std::sin(theta)), b(-a.y(), a.x());
    const Camera turned = photoPushbroomCamera({4.0, 35.0}, kFrame);
    for (const Eigen::Vector2d& p : samplePoints()) {
      const double d = planeDepth(p);
      const Eigen::Vector2d want = a * a.dot(p) * d / 4.0 + b * b.dot(p);
      QVERIFY((apply(turned, p, d).position - want).norm() < kPositionTolerance);
    }

    for (const PhotoXSlitParams& xs : {PhotoXSlitParams{}, PhotoXSlitParams{2.0, 0.5, 6.0}}) {
      const Camera camera = photoXSlitCamera(xs, kFrame);
      // The crossed-slits camera of focal f with its slits at depths -s_u, -s_v, then each axis
      // scaled to the photo's at the reference depth.
      XSlitParams slits;
      slits.focal = focal;
      slits.slit_u_depth = -xs.slit_u_behind;
      slits.slit_v_depth = -xs.slit_v_behind;
      const double dr = xs.reference_depth;
      const Eigen::Vector2d k((dr + xs.slit_u_behind) / dr, (dr + xs.slit_v_behind) / dr);
      for (const Eigen::Vector2d& p : samplePoints()) {
        const double d = planeDepth(p);
        const Eigen::Vector3d point = backProject(p, d, focal);
        const Eigen::Vector2d seen(focal * point.x() / (d + xs.slit_u_behind),
                                   focal * point.y() / (d + xs.slit_v_behind));
        QVERIFY(xslitRay(slits, seen).distanceTo(point) < 1e-9);
        QVERIFY((apply(camera, p, d).position - seen.cwiseProduct(k)).norm() < kPositionTolerance);
      }
    }

    // The parallax GLC: p' = p + e(p')/d, solved for p' by hand: (I − E/d) p' = p + e₀/d.
    const PhotoParallaxParams par{{0.15, -0.1}, {0.25, 0.1}, {-0.2, 0.3}};
    const Camera parallax = photoParallaxCamera(par, kFrame);
    const GlcParams parallax_glc = photoParallaxGlc(par, focal);
    // Stated with another focal, the same camera.
    const Camera other = photoGlcCamera(photoParallaxGlc(par, 0.45), 0.45, kFrame);
    Eigen::Matrix2d e;
    e << par.shift_per_u, par.shift_per_v;
    for (const Eigen::Vector2d& p : samplePoints()) {
      const double d = planeDepth(p);
      const Eigen::Vector2d want =
          (Eigen::Matrix2d::Identity() - e / d).inverse() * (p + par.shift / d);
      QVERIFY(glcRay(parallax_glc, want).distanceTo(backProject(p, d, focal)) < 1e-9);
      QVERIFY((apply(parallax, p, d).position - want).norm() < kPositionTolerance);
      QVERIFY((apply(other, p, d).position - want).norm() < kPositionTolerance);
    }
  }

  // The GLC that is the photo's pinhole (all rays through the centre, image = f·direction)
  // returns every pixel where it was; a pinhole of another focal f₂ scales by f₂/f; the presets'
  // neutral settings are the photo itself.
  void thePhotosOwnPinholeIsTheIdentity() {
    const double focal = 1.9;
    const std::array<Eigen::Vector4d, 3> through_centre = {Eigen::Vector4d(0, 0, -0.3, 0.2),
                                                           Eigen::Vector4d(0, 0, 0.4, 0.1),
                                                           Eigen::Vector4d(0, 0, 0.05, -0.35)};
    const Camera same = photoGlcCamera(glcFromTwoPlanes(through_centre, focal), focal, kFrame);
    const Camera longer = photoGlcCamera(glcFromTwoPlanes(through_centre, 2.4), focal, kFrame);
    const Camera neutral_xslit = photoXSlitCamera({0.0, 0.0, 3.0}, kFrame);
    const Camera neutral_glc = photoParallaxCamera({{0, 0}, {0, 0}, {0, 0}}, kFrame);
    for (const Eigen::Vector2d& p : samplePoints()) {
      const double d = planeDepth(p);
      for (const Camera* c : {&same, &neutral_xslit, &neutral_glc})
        QVERIFY((apply(*c, p, d).position - p).norm() < 1e-12);
      QVERIFY((apply(longer, p, d).position - p * 2.4 / focal).norm() < 1e-12);
    }
    // A pushbroom at its reference depth is the photo there too.
    const Camera pb = photoPushbroomCamera({2.0, 20.0}, kFrame);
    for (const Eigen::Vector2d& p : samplePoints())
      QVERIFY((apply(pb, p, 2.0).position - p).norm() < 1e-12);
  }

  // A pixel without depth (d = 0, a hole of the depth image) is the photo's centre itself: no
  // image, so the renderer leaves it out instead of placing it anywhere.
  void aPixelWithoutDepthHasNoImage() {
    for (const char* name : {"photo-pushbroom", "photo-xslit", "photo-glc"}) {
      const AttributeEvaluator eval(buildEffect(name, {}, kFrame).main());
      const float rgba[4] = {0.2f, 0.3f, 0.4f, 1.0f};
      AttributeEvaluator::Output out;
      eval.evaluate(0.3, -0.2, rgba, 0.0, out);
      QVERIFY2(!out.position_valid, name);
      eval.evaluate(0.3, -0.2, rgba, 4.0, out);
      QVERIFY2(out.position_valid, name);
    }
  }

  // End to end: the effects table's cameras at their defaults rendered through render() on a
  // photo whose colour encodes the source pixel (r = x/W, g = y/H) with depth a 3D plane
  // (inverse depth affine in the image: 1/d = α + β·p). At chosen output pixels the colour
  // must decode to the source point the header's ray geometry gives, solved by hand for the
  // plane: push-broom a·q = (a·p)/(d_r·(α + β·p)), b·q = b·p; crossed slits per axis
  // q = k·p/(1 + s(α + β·p)); parallax p = q − e(q)·(α + β·p).
  void renderPutsPixelsWhereTheRaysSay_data() {
    QTest::addColumn<QString>("effect");
    QTest::newRow("photo-pushbroom") << "photo-pushbroom";
    QTest::newRow("photo-xslit") << "photo-xslit";
    QTest::newRow("photo-glc") << "photo-glc";
  }
  void renderPutsPixelsWhereTheRaysSay() {
    QFETCH(QString, effect);
    const FrameSize frame{96, 72};
    const double alpha = 0.3;
    const Eigen::Vector2d beta(0.05, -0.08);
    ImageF photo(frame.width, frame.height, 3);
    ImageF depth(frame.width, frame.height, 1);
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) {
        photo.pixel(x, y)[0] = static_cast<float>((x + 0.5) / frame.width);
        photo.pixel(x, y)[1] = static_cast<float>((y + 0.5) / frame.height);
        photo.pixel(x, y)[2] = 0.5f;
        const Eigen::Vector2d p = normalizedFromPixel(frame, {x + 0.5, y + 0.5});
        depth.pixel(x, y)[0] = static_cast<float>(1.0 / (alpha + beta.dot(p)));
      }
    const Artcam camera = buildEffect(effect.toStdString(), {}, frame);
    RenderSummary summary;
    const ImageF out = render(RenderInputs::of(photo, &depth), camera, {}, &summary);
    QCOMPARE(out.width, frame.width);
    QCOMPARE(summary.path, RenderPath::Splat);

    // The source point of output point q, from the defaults of the table's row.
    const auto value = [&](const char* name, int i = 0) {
      return findParam(*findEffect(effect.toStdString()), name)->value[static_cast<size_t>(i)];
    };
    std::function<Eigen::Vector2d(const Eigen::Vector2d&)> sourceOf;
    if (effect == "photo-pushbroom") {
      const double dr = value("reference-depth"), t = value("angle") * std::numbers::pi / 180;
      const Eigen::Vector2d a(std::cos(t), std::sin(t)), b(-a.y(), a.x());
      sourceOf = [=](const Eigen::Vector2d& q) {
        // In the (a, b) frame: b·p = b·q, and x = a·p solves a·q·d_r·(α + β·a·x + β·b·(b·q)) = x,
        // linear in x.
        const double pb = b.dot(q), qa = a.dot(q);
        const double x = qa * dr * (alpha + beta.dot(b) * pb) / (1.0 - qa * dr * beta.dot(a));
        return Eigen::Vector2d(a * x + b * pb);
      };
    } else if (effect == "photo-xslit") {
      const double su = value("slit-u-behind"), sv = value("slit-v-behind"),
                   dr = value("reference-depth");
      sourceOf = [=](const Eigen::Vector2d& q) {
        // q_u·(1 + s_u·m) = k_u·p_u with m = α + β·p: two equations linear in p.
        const double ku = (dr + su) / dr, kv = (dr + sv) / dr;
        Eigen::Matrix2d m;
        m << ku - q.x() * su * beta.x(), -q.x() * su * beta.y(), -q.y() * sv * beta.x(),
            kv - q.y() * sv * beta.y();
        const Eigen::Vector2d rhs(q.x() * (1 + su * alpha), q.y() * (1 + sv * alpha));
        return Eigen::Vector2d(m.fullPivLu().solve(rhs));
      };
    } else {
      const Eigen::Vector2d e0(value("shift", 0), value("shift", 1)),
          eu(value("shift-per-u", 0), value("shift-per-u", 1)),
          ev(value("shift-per-v", 0), value("shift-per-v", 1));
      sourceOf = [=](const Eigen::Vector2d& q) {
        // p + e(q)·(β·p) = q − α·e(q).
        const Eigen::Vector2d eq = e0 + q.x() * eu + q.y() * ev;
        const Eigen::Matrix2d m = Eigen::Matrix2d::Identity() + eq * beta.transpose();
        return Eigen::Vector2d(m.fullPivLu().solve(q - alpha * eq));
      };
    }

    int checked = 0;
    double worst_px = 0.0;
    for (int y = 4; y < frame.height - 4; y += 5)
      for (int x = 4; x < frame.width - 4; x += 5) {
        const Eigen::Vector2d q = normalizedFromPixel(frame, {x + 0.5, y + 0.5});
        const Eigen::Vector2d p = sourceOf(q);
        // The expected source lies well inside the photo (no border ring), or skip the pixel.
        const Eigen::Vector2d src_px = pixelFromNormalized(frame, p);
        if (src_px.x() < 3 || src_px.y() < 3 || src_px.x() > frame.width - 3 ||
            src_px.y() > frame.height - 3)
          continue;
        const float* c = out.pixel(x, y);
        QVERIFY2(c[3] > 0.999f, qPrintable(QString("(%1, %2) alpha %3").arg(x).arg(y).arg(c[3])));
        const Eigen::Vector2d got_px(c[0] / c[3] * frame.width, c[1] / c[3] * frame.height);
        worst_px = std::max(worst_px, (got_px - src_px).norm());
        ++checked;
      }
    QVERIFY2(checked > 50, qPrintable(QString("only %1 pixels checked").arg(checked)));
    // The splat interpolates the mapped pixel centres linearly over each triangle: the map's
    // curvature over one pixel costs far less than this.
    QVERIFY2(worst_px < 0.05, qPrintable(QString("%1 px off").arg(worst_px)));
  }
};

QTEST_MAIN(TestMultiPerspective)
#include "test_multi_perspective.moc"
