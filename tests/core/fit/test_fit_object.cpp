// SPDX-License-Identifier: Apache-2.0
// Fitting object-space cameras (n = 4): the paper's §4 with 40 unknowns, 3 rows per match.
#include "core/fit/dlt.h"
#include "core/fit/fit_image.h"
#include "core/model/structure.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <Eigen/SVD>

using namespace artcam;

namespace {

Camera randomObjectCamera(double strength) {
  Camera cam = Camera::identity({Block{BlockKind::Position, 4}}, {}, {});
  for (Eigen::MatrixXd& q : cam.stages()[0].q) {
    Eigen::Matrix4d noise;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) noise(r, c) = test::uniform(-strength, strength);
    q += 0.5 * (noise + noise.transpose());
  }
  return cam;
}

Eigen::Vector3d mapPoint(const Camera& cam, const Eigen::Vector3d& p) {
  const Eigen::VectorXd z = cam.evaluateHomogeneous(Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0));
  return z.head<3>() / z[3];
}

std::vector<PointMatch> cloudMatches(const Camera& cam, int count) {
  std::vector<PointMatch> out;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d p(test::uniform(-1, 1), test::uniform(-1, 1), test::uniform(-1, 1));
    out.push_back({p, mapPoint(cam, p), true});
  }
  return out;
}

}  // namespace

class TestFitObject : public QObject {
  Q_OBJECT

 private slots:
  void minimumCountsFollowThePaper() {
    QCOMPARE(minimumMatches(ModelClass::Quadratic, 2), 9);
    QCOMPARE(minimumMatches(ModelClass::Quadratic, 3), 13);
  }

  void thirteenExactMatchesDetermineTheCamera() {
    const Camera truth = randomObjectCamera(0.1);
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary s = fitObjectCamera(cloudMatches(truth, 13), o);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QVERIFY2(s.record.max_px < 1e-9, s.report().c_str());
    for (int t = 0; t < 50; ++t) {
      const Eigen::Vector3d p(test::uniform(-1, 1), test::uniform(-1, 1), test::uniform(-1, 1));
      QVERIFY((mapPoint(s.camera, p) - mapPoint(truth, p)).norm() < 1e-7);
    }
  }

  void twelveAreRefused() {
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary s = fitObjectCamera(cloudMatches(randomObjectCamera(0.1), 12), o);
    QVERIFY(!s.status.ok);
    QVERIFY2(s.status.message.find("needs at least 13") != std::string::npos, s.status.message.c_str());
  }

  void coplanarPointsAreRefused() {
    const Camera truth = randomObjectCamera(0.1);
    std::vector<PointMatch> m;
    for (int k = 0; k < 30; ++k) {
      const Eigen::Vector3d p(test::uniform(-1, 1), test::uniform(-1, 1), 0.25);
      m.push_back({p, mapPoint(truth, p), true});
    }
    const FitSummary s = fitObjectCamera(m, {});
    QVERIFY(!s.status.ok || s.record.model == "translation");
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary q = fitObjectCamera(m, o);
    QVERIFY(!q.status.ok);
    QVERIFY2(q.status.message.find("one plane") != std::string::npos, q.status.message.c_str());
  }

  void projectiveDataStayProjective() {
    Eigen::Matrix4d h = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) h(r, c) += test::uniform(-0.1, 0.1);
    Stage stage;
    for (const Eigen::MatrixXd& q : liftHomography(h)) stage.q.push_back(q);
    const Camera truth({Block{BlockKind::Position, 4}}, {stage}, {}, {});
    const FitSummary s = fitObjectCamera(cloudMatches(truth, 40), {});
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QCOMPARE(s.record.model, std::string("homography"));
    QCOMPARE(analyseStructure(s.camera).geometry, GeometryClass::Homography);
    QVERIFY(s.record.max_px < 1e-8);
  }

  // From 200 matches on, the 3D DLT solves its 40×40 normal matrix. Its null vector must be the
  // design matrix's smallest right singular vector, computed here by an SVD of the design
  // matrix built in the test (the paper's §4 rows, eq 10 monomials): the same minimiser, an
  // independent evaluation.
  void normalEquationsMatchTheDesignMatrixSvd() {
    const Camera truth = randomObjectCamera(0.1);
    const int m = 300;
    Points src(3, m), dst(3, m);
    for (int k = 0; k < m; ++k) {
      const Eigen::Vector3d p(test::uniform(-1, 1), test::uniform(-1, 1), test::uniform(-1, 1));
      src.col(k) = p;
      dst.col(k) = mapPoint(truth, p) +
                   Eigen::Vector3d(test::uniform(-1e-3, 1e-3), test::uniform(-1e-3, 1e-3), test::uniform(-1e-3, 1e-3));
    }
    Eigen::MatrixXd design = Eigen::MatrixXd::Zero(3 * m, 40);
    for (int k = 0; k < m; ++k) {
      const double x[4] = {src(0, k), src(1, k), src(2, k), 1.0};
      Eigen::Matrix<double, 10, 1> chi;
      int c = 0;
      for (int j = 0; j < 4; ++j)
        for (int l = j; l < 4; ++l) chi[c++] = (j == l ? 1.0 : 2.0) * x[j] * x[l];
      for (int i = 0; i < 3; ++i) {
        design.block<1, 10>(3 * k + i, 10 * i) = chi.transpose();
        design.block<1, 10>(3 * k + i, 30) = -dst(i, k) * chi.transpose();
      }
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design, Eigen::ComputeThinV);
    const Eigen::VectorXd expected = svd.matrixV().col(39);
    const DltSolution s = solveQuadraticDlt(src, dst);
    QCOMPARE(s.null_dimension, 1);
    Eigen::VectorXd got(40);
    for (int i = 0; i < 4; ++i) {
      int c = 10 * i;
      for (int j = 0; j < 4; ++j)
        for (int l = j; l < 4; ++l) got[c++] = s.q[i](j, l);
    }
    got.normalize();
    if (got.dot(expected) < 0) got = -got;
    QVERIFY2((got - expected).norm() < 1e-7, qPrintable(QString::number((got - expected).norm())));
    // And the fit through it maps like the truth to the noise level.
    std::vector<PointMatch> matches;
    for (int k = 0; k < m; ++k) matches.push_back({src.col(k), dst.col(k), true});
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary fit = fitObjectCamera(matches, o);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    QVERIFY2(fit.record.rms_px < 2e-3, fit.report().c_str());
  }
};

QTEST_GUILESS_MAIN(TestFitObject)
#include "test_fit_object.moc"
