// SPDX-License-Identifier: Apache-2.0
// A rational-camera warp of the bundled photo checked pixel by pixel against an independent
// evaluation written here: the camera's own eq 3/5 evaluation (Camera::evaluateHomogeneous,
// not the renderer's pixel tensors), solved for each sampled output pixel by Newton with a
// finite-difference Jacobian from a grid of starts, then sampled by a plain bilinear filter.
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/warp.h"
#include "tests/support/test_support.h"

#include <OpenImageIO/imagebuf.h>

#include "tests/core/render/photo_fixture.h"

#include <QtTest/QtTest>

#include <Eigen/LU>

#include <cmath>
#include <optional>
#include <vector>

using namespace artcam;

namespace {

struct Forward {
  Eigen::Vector2d target;
  double denominator;
};

// Source pixel → target pixel through the model's own evaluation (eq 3, then eq 5's division).
std::optional<Forward> forward(const Camera& camera, const Eigen::Vector2d& s) {
  const Eigen::Vector2d n = normalizedFromPixel(camera.sourceSize(), s);
  const Eigen::VectorXd z = camera.evaluateHomogeneous(Eigen::Vector3d(n.x(), n.y(), 1.0));
  if (z[2] == 0.0) return std::nullopt;
  const Eigen::Vector2d t = pixelFromNormalized(camera.targetSize(), Eigen::Vector2d(z[0] / z[2], z[1] / z[2]));
  if (!t.allFinite()) return std::nullopt;
  return Forward{t, z[2]};
}

std::optional<Eigen::Matrix2d> jacobianFd(const Camera& camera, const Eigen::Vector2d& s) {
  const double h = 1e-4;
  Eigen::Matrix2d j;
  for (int c = 0; c < 2; ++c) {
    Eigen::Vector2d d = Eigen::Vector2d::Zero();
    d[c] = h;
    const auto a = forward(camera, s + d), b = forward(camera, s - d);
    if (!a || !b) return std::nullopt;
    j.col(c) = (a->target - b->target) / (2 * h);
  }
  return j;
}

struct Root {
  Eigen::Vector2d s;
  bool valid;  // on the centre's side of the pole and not folded
};

// All distinct roots of forward(s) = t found from a grid of starts.
std::vector<Root> solve(const Camera& camera, const Eigen::Vector2d& t, double centre_den,
                        double centre_det) {
  const FrameSize src = camera.sourceSize();
  std::vector<Eigen::Vector2d> starts{t};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) starts.emplace_back((i + 0.5) * src.width / 3, (j + 0.5) * src.height / 3);
  std::vector<Root> roots;
  for (const Eigen::Vector2d& start : starts) {
    Eigen::Vector2d s = start;
    bool converged = false;
    for (int it = 0; it < 60; ++it) {
      const auto f = forward(camera, s);
      const auto j = jacobianFd(camera, s);
      if (!f || !j || std::abs(j->determinant()) < 1e-12) break;
      const Eigen::Vector2d r = f->target - t;
      if (r.norm() < 1e-9) {
        converged = true;
        break;
      }
      Eigen::Vector2d step = -j->inverse() * r;
      const double len = step.norm();
      if (len > 50.0) step *= 50.0 / len;  // damping: no leaps across the frame
      s += step;
    }
    if (!converged) continue;
    bool known = false;
    for (const Root& root : roots) known = known || (root.s - s).norm() < 1e-5;
    if (known) continue;
    const auto f = forward(camera, s);
    const auto j = jacobianFd(camera, s);
    roots.push_back({s, f && j && (f->denominator > 0) == (centre_den > 0) &&
                            (j->determinant() > 0) == (centre_det > 0)});
  }
  return roots;
}

// Plain bilinear with pixel centres at i + 0.5; outside taps are transparent (black, alpha 0).
void bilinear(const ImageF& img, const Eigen::Vector2d& s, float* out) {
  const double fx = s.x() - 0.5, fy = s.y() - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  double sum[3] = {0, 0, 0}, cover = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double xi = x0 + dx, yi = y0 + dy;
      if (xi < 0 || yi < 0 || xi >= img.width || yi >= img.height) continue;
      const double w = (dx ? fx - x0 : 1 - (fx - x0)) * (dy ? fy - y0 : 1 - (fy - y0));
      const float* p = img.pixel(static_cast<int>(xi), static_cast<int>(yi));
      for (int c = 0; c < 3; ++c) sum[c] += w * p[c];
      cover += w;
    }
  for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(sum[c]);
  out[3] = static_cast<float>(cover);
}

}  // namespace

class TestWarpReference : public QObject {
  Q_OBJECT

 private slots:
  void rationalWarpMatchesIndependentEvaluation_data() {
    QTest::addColumn<bool>("fitted_seed");
    QTest::newRow("fitted inverse seed") << true;
    QTest::newRow("neighbour and linear seeds") << false;
  }

  void rationalWarpMatchesIndependentEvaluation() {
    QFETCH(bool, fitted_seed);
    const ImageF photo = test::readLinearPhoto(test::resourcePath("coffee.png"));
    QVERIFY(!photo.empty());
    QCOMPARE(photo.channels, 3);
    const FrameSize size{photo.width, photo.height};
    test::rng().seed(7);
    const Camera camera = test::randomRationalCamera(size, size, 0.15);
    QCOMPARE(analyseStructure(camera).geometry, GeometryClass::Rational);

    WarpOptions options;
    options.coordinates.fit_inverse_seed = fitted_seed;
    WarpSummary summary;
    const ImageF out = warpImage(photo, camera, options, &summary);
    QCOMPARE(summary.kernel, std::string("rational"));
    if (fitted_seed) QVERIFY2(summary.note.empty(), summary.note.c_str());
    QCOMPARE(out.channels, 4);
    QCOMPARE(out.alpha_channel, 3);

    const Eigen::Vector2d centre(size.width / 2.0, size.height / 2.0);
    const double centre_den = forward(camera, centre)->denominator;
    const double centre_det = jacobianFd(camera, centre)->determinant();
    double max_diff = 0.0;
    int checked = 0, no_preimage = 0, ambiguous = 0;
    for (int y = 1; y < out.height; y += 6) {
      for (int x = 2; x < out.width; x += 6) {
        const std::vector<Root> roots = solve(camera, Eigen::Vector2d(x + 0.5, y + 0.5), centre_den, centre_det);
        std::vector<Eigen::Vector2d> valid;
        for (const Root& r : roots)
          if (r.valid) valid.push_back(r.s);
        if (valid.size() > 1) ++ambiguous;
        float want[4] = {0, 0, 0, 0};
        if (valid.empty()) ++no_preimage;
        else bilinear(photo, valid.front(), want);
        const float* got = out.pixel(x, y);
        for (int c = 0; c < 4; ++c) {
          QVERIFY(std::isfinite(got[c]));
          max_diff = std::max(max_diff, static_cast<double>(std::abs(got[c] - want[c])));
        }
        ++checked;
      }
    }
    qInfo("rational warp vs independent per-pixel solve: max |diff| %.3g over %d pixels "
          "(%d without preimage), %.1f ms, %s",
          max_diff, checked, no_preimage, summary.render_ms, summary.note.c_str());
    QCOMPARE(ambiguous, 0);
    QVERIFY(checked > 5000);
    QVERIFY2(max_diff < 1e-4, "the rational warp disagrees with the independent evaluation");
  }
};

QTEST_GUILESS_MAIN(TestWarpReference)
#include "test_warp_reference.moc"
