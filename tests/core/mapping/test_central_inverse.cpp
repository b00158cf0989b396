// SPDX-License-Identifier: Apache-2.0
// The closed-form inverse of central maps (central_inverse.h): which maps are central, the
// round trip through the forward map, inverse.h's pole and fold rule on both roots, and the
// SIMD lanes against the scalar code bit for bit.
#include "core/effects/image_warps.h"
#include "core/model/camera.h"
#include "core/mapping/central_inverse.h"
#include "core/mapping/coordinates.h"
#include "core/mapping/inverse.h"
#include "core/mapping/rational_map.h"
#include "tests/support/test_support.h"

#include <Eigen/LU>
#include <QtTest/QtTest>

#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

using namespace artcam;

namespace {

const FrameSize kFrame{1200, 800};

Camera cameraOf(const Eigen::Matrix3d& qu, const Eigen::Matrix3d& qv, const Eigen::Matrix3d& qw) {
  return Camera({Block{BlockKind::Position, 3}}, {Stage{{qu, qv, qw}}}, kFrame, kFrame);
}

// F(u) = c_t + H ũ (l · ũ) / (1 + a |u − c_s|²) in normalised coordinates, H ũ = H₂ (u − c_s).
Camera centralCamera(const Eigen::Vector2d& cs, const Eigen::Vector2d& ct, const Eigen::Matrix2d& h2,
                     const Eigen::Vector3d& l, double a) {
  const Eigen::Vector3d centre(cs.x(), cs.y(), 1.0);
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();  // 1 + a |u − c_s|² as a form in ũ
  q.topLeftCorner<2, 2>() = a * Eigen::Matrix2d::Identity();
  q.block<2, 1>(0, 2) = q.block<1, 2>(2, 0).transpose() = -a * cs;
  q(2, 2) = 1.0 + a * cs.squaredNorm();
  Eigen::Matrix3d out[2];
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector3d h;
    h.head<2>() = h2.row(k).transpose();
    h(2) = -h2.row(k).dot(cs);
    out[k] = symmetricOuter(l, h) + ct(k) * q;
  }
  return cameraOf(out[0], out[1], q);
}

// inverse.h's rule at s: the source centre's side of the pole curve and its fold.
bool onCentreSide(const RationalMap& map, const CentreReference& centre, const Eigen::Vector2d& s,
                  Eigen::Vector2d& f) {
  Eigen::Matrix2d j;
  unsigned signs = 0;
  if (!map.evaluate(s, f, &j, &signs)) return false;
  return (signs & 1u) == (centre.denominator_signs & 1u) && (j.determinant() > 0.0) == centre.det_positive;
}

struct Case {
  Camera camera;
  bool far_roots;  // the frame centre lies beyond c_s's fold: the preimages are far roots
};

// The parallel form in normalised coordinates: a = n · F = (k · ũ) / (g · ũ) and
// b = d · F = ũᵀ P ũ / ((l · ũ)(g · ũ)), n at 20°, a finite pencil centre and A = c̃ᵀ P c̃ ≠ 0.
// `pole`: g's line u = −1/0.9 crosses the tested region just left of the frame.
Camera parallelCamera(bool pole) {
  const double angle = 20.0 * M_PI / 180.0;
  const Eigen::Vector2d n(std::cos(angle), std::sin(angle)), d(-n.y(), n.x());
  const Eigen::Vector3d k(1.0, 0.1, 0.05), l(0.05, 0.1, 1.0);
  const Eigen::Vector3d g = pole ? Eigen::Vector3d(0.9, 0.0, 1.0) : Eigen::Vector3d(0.1, -0.05, 1.0);
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  p(0, 0) = 0.2;
  p(0, 1) = p(1, 0) = 0.05;
  p(1, 2) = p(2, 1) = 0.5;
  const Eigen::Matrix3d lk = symmetricOuter(l, k);
  return cameraOf(n.x() * lk + d.x() * p, n.y() * lk + d.y() * p, symmetricOuter(l, g));
}

Case caseNamed(const QByteArray& name) {
  if (name == "twist-strong") return {twistCamera(1.0, kFrame), false};
  if (name == "parallel") return {parallelCamera(false), false};
  if (name == "parallel-pole") return {parallelCamera(true), false};
  if (name == "barrel-strong") return {radialLensCamera(-0.6, kFrame), false};
  if (name == "pincushion-strong") return {radialLensCamera(0.4, kFrame), false};
  if (name == "decentred")
    return {centralCamera({0.15, -0.1}, {0.05, 0.08}, (Eigen::Matrix2d() << 1.1, 0.2, -0.1, 0.9).finished(),
                          {0.1, -0.05, 1.0}, 0.5),
            false};
  // c_s at 1.3 with its fold circle at 1/√2: the frame centre, and most of the frame, beyond it.
  return {centralCamera({1.3, 0.0}, {0.0, 0.0}, Eigen::Matrix2d::Identity(), {0.0, 0.0, 1.0}, 2.0), true};
}

}  // namespace

class TestCentralInverse : public QObject {
  Q_OBJECT

 private slots:
  void radialLensesAreCentral() {
    for (double k : {-0.6, -0.15, 0.15, 0.4}) {
      const RationalMap map(radialLensCamera(k, kFrame), kFrame, kFrame);
      const std::optional<CentreReference> centre = centreReference(map, kFrame);
      QVERIFY(centre);
      const std::optional<CentralInverse> inverse = CentralInverse::detect(map, kFrame, *centre);
      QVERIFY2(inverse, qPrintable(QString("k = %1").arg(k)));
      // Radial about the frame's centre, which maps to itself.
      QVERIFY((inverse->centreSource() - Eigen::Vector2d(600, 400)).norm() < 1e-6);
      QVERIFY((inverse->centreTarget() - Eigen::Vector2d(600, 400)).norm() < 1e-6);
    }
  }

  // The twist moves outputs along vertical lines: the parallel form, for any rate.
  void twistIsParallel() {
    for (double rate : {-1.0, -0.3, 0.3, 1.0}) {
      const RationalMap map(twistCamera(rate, kFrame), kFrame, kFrame);
      const std::optional<CentreReference> centre = centreReference(map, kFrame);
      QVERIFY(centre);
      const std::optional<CentralInverse> inverse = CentralInverse::detect(map, kFrame, *centre);
      QVERIFY2(inverse && inverse->parallel(), qPrintable(QString("rate = %1").arg(rate)));
    }
    const RationalMap barrel(radialLensCamera(-0.6, kFrame), kFrame, kFrame);
    const std::optional<CentralInverse> radial = CentralInverse::detect(barrel, kFrame, *centreReference(barrel, kFrame));
    QVERIFY(radial && !radial->parallel());
  }

  // A radial lens with a small twist added is neither form, nor is a twist with a little
  // barrel, nor a map whose numerators share no line with its denominator: the closed form
  // would be a silently wrong inverse.
  void otherMapsAreNot() {
    Camera bent = radialLensCamera(-0.6, kFrame);
    const Stage& stage = bent.stages().front();
    Eigen::Matrix3d qv = stage.q[1];
    qv(0, 1) += 1e-4;
    qv(1, 0) += 1e-4;
    const Camera nearly = cameraOf(stage.q[0], qv, stage.q[2]);
    const Stage twist = twistCamera(1.0, kFrame).stages().front();
    Eigen::Matrix3d qw = twist.q[2];
    qw(0, 0) += 1e-4;
    qw(1, 1) += 1e-4;
    const Camera twisted_barrel = cameraOf(twist.q[0], twist.q[1], qw);
    Eigen::Matrix3d general_u = Eigen::Matrix3d::Zero(), general_v = Eigen::Matrix3d::Zero();
    general_u(0, 2) = general_u(2, 0) = 0.5;
    general_u(1, 1) = 0.1;
    general_v(1, 2) = general_v(2, 1) = 0.5;
    general_v(0, 0) = 0.1;
    const Camera general = cameraOf(general_u, general_v, Eigen::Vector3d(0, 0, 1) * Eigen::RowVector3d(0, 0, 1));
    for (const Camera* camera : {&nearly, &twisted_barrel, &general}) {
      const RationalMap map(*camera, kFrame, kFrame);
      const std::optional<CentreReference> centre = centreReference(map, kFrame);
      QVERIFY(centre);
      QVERIFY(!CentralInverse::detect(map, kFrame, *centre));
    }
  }

  void roundTripsThroughForwardMap_data() {
    QTest::addColumn<QByteArray>("name");
    for (const char* name :
         {"barrel-strong", "pincushion-strong", "decentred", "centre-beyond-fold", "twist-strong", "parallel",
          "parallel-pole"})
      QTest::newRow(name) << QByteArray(name);
  }

  // Every source point of a grid on the centre's side (inverse.h) maps forward to t, and the
  // inverse of t is that point again; every output point the inverse solves is a preimage on
  // the centre's side. Together: no preimage missed, none made up, and each exact.
  void roundTripsThroughForwardMap() {
    QFETCH(QByteArray, name);
    const Case c = caseNamed(name);
    const RationalMap map(c.camera, kFrame, kFrame);
    const std::optional<CentreReference> centre = centreReference(map, kFrame);
    QVERIFY(centre);
    const std::optional<CentralInverse> inverse = CentralInverse::detect(map, kFrame, *centre);
    QVERIFY(inverse);
    double worst = 0.0;
    long long sources = 0;
    for (double y = -200.5; y < 1000; y += 9.0)
      for (double x = -300.5; x < 1500; x += 11.0) {
        const Eigen::Vector2d s(x, y);
        Eigen::Vector2d t;
        if (!onCentreSide(map, *centre, s, t)) continue;
        Eigen::Vector2d back;
        QVERIFY2(inverse->solve(t, back), qPrintable(QString("source %1,%2 lost").arg(x).arg(y)));
        worst = std::max(worst, (back - s).norm());
        ++sources;
      }
    long long solved = 0, without = 0;
    double residual = 0.0;
    for (double y = -100.25; y < 900; y += 7.0)
      for (double x = -100.25; x < 1300; x += 5.0) {
        const Eigen::Vector2d t(x, y);
        Eigen::Vector2d s, f;
        if (!inverse->solve(t, s)) {
          ++without;
          continue;
        }
        QVERIFY2(onCentreSide(map, *centre, s, f), qPrintable(QString("output %1,%2").arg(x).arg(y)));
        residual = std::max(residual, (f - t).norm());
        ++solved;
      }
    qInfo("%s: %lld sources back within %.3g px; %lld outputs solved (residual %.3g px), %lld without",
          name.constData(), sources, worst, solved, residual, without);
    QVERIFY(sources > 1000);
    QVERIFY(solved > 1000);
    QVERIFY2(worst < 1e-6, qPrintable(QString::number(worst)));
    QVERIFY2(residual < 1e-6, qPrintable(QString::number(residual)));
    // Beyond the fold, or the pole.
    if (name == "barrel-strong" || name == "parallel-pole" || c.far_roots) QVERIFY(without > 0);
  }

  // The AVX2 and AVX-512 lanes give the scalar code's positions bit for bit, for runs of any
  // length and start, with no NaN and position 0 wherever there is no preimage.
  void lanesAgreeWithScalar_data() { roundTripsThroughForwardMap_data(); }
  void lanesAgreeWithScalar() {
    QFETCH(QByteArray, name);
    const RationalMap map(caseNamed(name).camera, kFrame, kFrame);
    const std::optional<CentreReference> centre = centreReference(map, kFrame);
    QVERIFY(centre);
    const std::optional<CentralInverse> inverse = CentralInverse::detect(map, kFrame, *centre);
    QVERIFY(inverse);
    constexpr int kMax = 300;
    long long valid = 0, compared = 0;
    for (int y = 0; y < kFrame.height; y += 13)
      for (const auto& [x0, n] : {std::pair{0, 256}, std::pair{17, 255}, std::pair{640, 61}, std::pair{1195, 5}}) {
        float sx[3][kMax], sy[3][kMax];
        unsigned char ok[3][kMax];
        for (int simd = 0; simd < 3; ++simd) {
          std::memset(sx[simd], 0x7f, sizeof sx[simd]);  // garbage the span must overwrite
          std::memset(sy[simd], 0x7f, sizeof sy[simd]);
          inverse->span(y, x0, n, sx[simd], sy[simd], ok[simd], simd);
        }
        for (int i = 0; i < n; ++i) {
          QVERIFY(std::isfinite(sx[0][i]) && std::isfinite(sy[0][i]));
          if (!ok[0][i]) QVERIFY(sx[0][i] == 0.0f && sy[0][i] == 0.0f);
          valid += ok[0][i];
          for (int simd = 1; simd < 3; ++simd) {
            QCOMPARE(ok[simd][i], ok[0][i]);
            QVERIFY(std::memcmp(&sx[simd][i], &sx[0][i], sizeof(float)) == 0);
            QVERIFY(std::memcmp(&sy[simd][i], &sy[0][i], sizeof(float)) == 0);
            ++compared;
          }
          // The span's pixel is the point solve's.
          Eigen::Vector2d s;
          const bool solved = inverse->solve({x0 + i + 0.5, y + 0.5}, s);
          QCOMPARE(solved, ok[0][i] != 0);
          if (solved) QVERIFY(sx[0][i] == static_cast<float>(s.x()) && sy[0][i] == static_cast<float>(s.y()));
        }
      }
    QVERIFY(valid > 0);
    QVERIFY(compared > 0);
  }

  // Through the fused kernel: the central path and the general one (cells, quadtree, Newton)
  // agree on every pixel of a strong barrel's and a strong twist's frame, within the 1/256 px
  // budget.
  void kernelPathsAgree_data() {
    QTest::addColumn<bool>("twist");
    QTest::newRow("barrel-strong") << false;
    QTest::newRow("twist-strong") << true;
  }
  void kernelPathsAgree() {
    QFETCH(bool, twist);
    const FrameSize size{1500, 1000};
    const Camera camera = twist ? twistCamera(1.0, size) : radialLensCamera(-0.6, size);
    const CameraStructure structure = analyseStructure(camera);
    CoordinateOptions general;
    general.central_inverse = false;
    const KernelChoice a = makeCoordinateKernel(camera, structure, size, size, CoordinateOptions{}, 2);
    const KernelChoice b = makeCoordinateKernel(camera, structure, size, size, general, 2);
    float ax[kSpanPixels], ay[kSpanPixels], bx[kSpanPixels], by[kSpanPixels];
    unsigned char aok[kSpanPixels], bok[kSpanPixels];
    double worst = 0.0;
    long long differ = 0, both = 0;
    for (int y = 0; y < size.height; ++y) {
      RowState sa, sb;
      for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, size.width - x0);
        a.kernel->span(y, x0, n, ax, ay, aok, sa);
        b.kernel->span(y, x0, n, bx, by, bok, sb);
        for (int i = 0; i < n; ++i) {
          // Beyond the filters' reach the general path may leave a pixel invalid, or its
          // position inexact: the pixel renders transparent either way.
          const bool in_reach = ax[i] > -4 && ay[i] > -4 && ax[i] < size.width + 4 && ay[i] < size.height + 4;
          if (aok[i] && bok[i]) {
            if (!in_reach) continue;  // transparent whatever the position
            worst = std::max(worst, static_cast<double>(std::hypot(ax[i] - bx[i], ay[i] - by[i])));
            ++both;
          } else if (bok[i] || (aok[i] && in_reach)) {
            ++differ;
          }
        }
      }
    }
    qInfo("kernel paths: %lld pixels both, %lld differ, worst %.3g px", both, differ, worst);
    QVERIFY(both > 0);
    QCOMPARE(differ, 0LL);
    QVERIFY2(worst <= 1.0 / 256.0, qPrintable(QString::number(worst)));
  }
};

QTEST_GUILESS_MAIN(TestCentralInverse)
#include "test_central_inverse.moc"
