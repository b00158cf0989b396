// SPDX-License-Identifier: Apache-2.0
// The camera family against its ray definitions: for random poses and points, the image point
// that the TENSOR gives (Camera::evaluate, eq 3/5) must be the image point whose ray (written
// from the geometry) passes through the point, to 1e-9 relative, and the other way round; the
// nearness output must fall along every ray. GLCs built from the rays of the other cameras must
// reproduce them.
#include "core/cameras/glc.h"
#include "core/cameras/projective_cameras.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <functional>

using namespace artcam;

namespace {

constexpr double kTol = 1e-9;

CameraPose randomPose() {
  const Eigen::Vector3d eye(test::uniform(-5, 5), test::uniform(-5, 5), test::uniform(-5, 5));
  const Eigen::Vector3d target(test::uniform(-1, 1), test::uniform(-1, 1), test::uniform(-1, 1));
  return CameraPose::lookAt(eye, target);
}

// (u, v, nearness) of a world point through an object camera.
Eigen::Vector3d project(const Camera& cam, const Eigen::Vector3d& p) {
  const Eigen::VectorXd y = cam.evaluate(Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0));
  return y.head<3>();
}

// A world point in front of the camera: camera coordinates x, y in [-1, 1]·z, z in [zmin, zmax].
Eigen::Vector3d pointInFront(const CameraPose& pose, double zmin = 2, double zmax = 8) {
  const double z = test::uniform(zmin, zmax);
  return pose.worldFromCamera(
      Eigen::Vector3d(test::uniform(-0.8, 0.8) * z, test::uniform(-0.8, 0.8) * z, z));
}

struct Family {
  const char* name;
  Camera camera;
  CameraPose pose;
  std::function<std::optional<Ray>(const Eigen::Vector2d&)> ray;
  double zmin = 2;  // scene depths beyond the foci
};

std::vector<Family> families() {
  std::vector<Family> out;
  {
    PinholeParams p;
    p.focal = 1.7;
    p.principal = {0.1, -0.05};
    p.pose = randomPose();
    out.push_back({"pinhole", pinholeCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return std::optional(pinholeRay(p, i)); }});
  }
  {
    OrthographicParams p;
    p.scale = 0.3;
    p.pose = randomPose();
    out.push_back({"orthographic", orthographicCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return std::optional(orthographicRay(p, i)); }});
  }
  {
    PushbroomParams p;
    p.focal = 1.5;
    p.scale = 0.4;
    p.pose = randomPose();
    out.push_back({"push-broom", pushbroomCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return std::optional(pushbroomRay(p, i)); }});
  }
  {
    XSlitParams p;
    p.focal = 1.2;
    p.slit_u_depth = 0.5;
    p.slit_v_depth = -0.7;
    p.pose = randomPose();
    out.push_back({"crossed-slits", xslitCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return std::optional(xslitRay(p, i)); }});
  }
  {
    RationalLensParams p;
    p.focal = 1.8;
    p.k = 0.15;
    p.pose = randomPose();
    out.push_back({"rational lens (barrel)", rationalLensCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return rationalLensRay(p, i); }});
    p.k = -0.1;
    out.push_back({"rational lens (pin-cushion)", rationalLensCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return rationalLensRay(p, i); }});
  }
  {
    // A twisted GLC: generators cross z = 0 on a small rotated triangle and z = 1 on a large one.
    GlcParams p = glcFromTwoPlanes(
        {Eigen::Vector4d(-0.2, 0.1, -0.6, -0.5), Eigen::Vector4d(0.15, 0.2, 0.6, -0.5),
         Eigen::Vector4d(0.0, -0.25, 0.0, 0.6)},
        1.5);
    p.pose = randomPose();
    out.push_back({"GLC", glcCamera(p), p.pose,
                   [p](const Eigen::Vector2d& i) { return std::optional(glcRay(p, i)); }, 2.5});
  }
  return out;
}

}  // namespace

class TestFamily : public QObject {
  Q_OBJECT

 private slots:
  void projectedPointLiesOnItsRay() {
    for (const Family& f : families()) {
      for (int t = 0; t < 200; ++t) {
        const Eigen::Vector3d p = pointInFront(f.pose, f.zmin);
        const Eigen::Vector3d y = project(f.camera, p);
        QVERIFY2(y.allFinite(), f.name);
        QVERIFY2(y[2] > 0,
                 qPrintable(QString("%1: nearness %2 for a point in front").arg(f.name).arg(y[2])));
        const auto ray = f.ray(y.head<2>());
        QVERIFY2(ray, f.name);
        const double scale = (p - ray->origin).norm() + 1e-300;
        QVERIFY2(ray->distanceTo(p) <= kTol * scale,
                 qPrintable(QString("%1: point %2 from its ray (relative)")
                                .arg(f.name)
                                .arg(ray->distanceTo(p) / scale)));
      }
    }
  }

  void pointsOnARayProjectToItsImagePointAndNearnessFalls() {
    for (const Family& f : families()) {
      for (int t = 0; t < 100; ++t) {
        const Eigen::Vector2d image(test::uniform(-0.7, 0.7), test::uniform(-0.7, 0.7));
        const auto ray = f.ray(image);
        QVERIFY2(ray, f.name);
        // Parameters along the ray at camera depths beyond the foci (direction has z = 1 in
        // camera coordinates, origin at z = 0).
        const double t1 = test::uniform(f.zmin, 5), t2 = t1 + test::uniform(0.5, 3);
        const Eigen::Vector3d near = ray->origin + t1 * ray->direction;
        const Eigen::Vector3d far = ray->origin + t2 * ray->direction;
        const Eigen::Vector3d yn = project(f.camera, near), yf = project(f.camera, far);
        for (const Eigen::Vector3d& y : {yn, yf})
          QVERIFY2((y.head<2>() - image).norm() <= kTol * (1 + image.norm()),
                   qPrintable(QString("%1: image point off by %2")
                                  .arg(f.name)
                                  .arg((y.head<2>() - image).norm())));
        QVERIFY2(yn[2] > yf[2] && yf[2] > 0,
                 qPrintable(QString("%1: nearness %2 then %3").arg(f.name).arg(yn[2]).arg(yf[2])));
      }
    }
  }

  void pinholeMatchesTheTextbookMatrix() {
    PinholeParams p;
    p.focal = 2.5;
    p.principal = {0.2, 0.1};
    p.pose = randomPose();
    const Camera cam = pinholeCamera(p);
    for (int t = 0; t < 50; ++t) {
      const Eigen::Vector3d w = pointInFront(p.pose);
      const Eigen::Vector3d c = p.pose.cameraFromWorld(w);
      const Eigen::Vector3d y = project(cam, w);
      QVERIFY(std::abs(y[0] - (2.5 * c.x() / c.z() + 0.2)) < 1e-12 * (1 + std::abs(y[0])));
      QVERIFY(std::abs(y[1] - (2.5 * c.y() / c.z() + 0.1)) < 1e-12 * (1 + std::abs(y[1])));
      QVERIFY(std::abs(y[2] - 1.0 / c.z()) < 1e-12);  // inverse depth, for the z-buffer
    }
    // Behind the camera: nearness negative, so the renderer drops it.
    QVERIFY(project(cam, p.pose.worldFromCamera(Eigen::Vector3d(0.1, 0.2, -3)))[2] < 0);
  }

  void generalRationalLensMatchesLiftedCoordinates() {
    Eigen::Matrix<double, 3, 6> a;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 6; ++c) a(r, c) = test::uniform(-0.2, 0.2);
    a(0, 3) += 2;
    a(1, 4) += 2;
    a(2, 5) += 1;
    const CameraPose pose = randomPose();
    const Camera cam = rationalLensCamera(a, pose);
    for (int t = 0; t < 50; ++t) {
      const Eigen::Vector3d w = pointInFront(pose);
      const Eigen::Vector3d c = pose.cameraFromWorld(w);
      Eigen::Matrix<double, 6, 1> chi;
      chi << c.x() * c.x(), c.x() * c.y(), c.y() * c.y(), c.x() * c.z(), c.y() * c.z(),
          c.z() * c.z();
      const Eigen::Vector3d h = a * chi;
      const Eigen::Vector3d y = project(cam, w);
      QVERIFY((y.head<2>() - h.head<2>() / h[2]).norm() < 1e-10 * (1 + y.head<2>().norm()));
    }
  }

  void glcReproducesTheOtherCamerasFromTheirRays() {
    // Three rays of a camera, as generators with their own image points, make a GLC that
    // projects every point as the camera does (pinhole, orthographic, push-broom and crossed
    // slits are all GLCs [YM04]).
    for (const Family& f : families()) {
      if (QString(f.name).startsWith("rational") || QString(f.name) == "GLC")
        continue;  // not linear
      GlcParams g;
      g.pose = f.pose;
      const Eigen::Vector2d images[3] = {{-0.5, -0.4}, {0.6, -0.3}, {0.1, 0.7}};
      for (int i = 0; i < 3; ++i) {
        const Ray r = *f.ray(images[i]);
        const Eigen::Vector3d o = f.pose.cameraFromWorld(r.origin);
        const Eigen::Vector3d d = f.pose.rotation * r.direction;
        const Eigen::Vector3d at0 = o - (o.z() / d.z()) * d, at1 = at0 + d / d.z();
        g.rays[i] = {at0.head<2>(), at1.head<2>(), images[i]};
      }
      const Camera glc = glcCamera(g);
      for (int t = 0; t < 50; ++t) {
        const Eigen::Vector3d p = pointInFront(f.pose);
        const Eigen::Vector3d a = project(f.camera, p), b = project(glc, p);
        QVERIFY2((a.head<2>() - b.head<2>()).norm() < kTol * (1 + a.head<2>().norm()),
                 qPrintable(QString("%1 as a GLC: off by %2")
                                .arg(f.name)
                                .arg((a.head<2>() - b.head<2>()).norm())));
      }
    }
  }

  void degenerateConstructionsAreRefused() {
    XSlitParams x;
    x.slit_u_depth = x.slit_v_depth = 1.0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, xslitCamera(x));
    PinholeParams p;
    p.focal = 0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, pinholeCamera(p));
    GlcParams g = glcFromTwoPlanes(
        {Eigen::Vector4d(0, 0, 0, 0), Eigen::Vector4d(0, 0, 1, 1), Eigen::Vector4d(0, 0, 2, 2)}, 1);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, glcCamera(g));  // collinear images
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, CameraPose::lookAt({0, 0, 0}, {0, 1, 0}));
  }
};

QTEST_GUILESS_MAIN(TestFamily)
#include "test_family.moc"
