// SPDX-License-Identifier: Apache-2.0
// Colour calibration: synthetic colour transforms recovered from samples
// (noise-free to round-off, noisy to what the noise allows), the ladder picking the simplest
// adequate model, root-polynomial never stored, outliers rejected by the robust fit, refusals
// with their cause, and the written camera evaluated through eq 3/5 (Camera::evaluate), an
// evaluation path independent of ColourMap::apply.
#include "core/colour/colour_difference.h"
#include "core/colour/colour_map.h"
#include "core/fit/fit_colour.h"
#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

using namespace artcam;

namespace {

using Transform = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

Eigen::Vector3d randomColour(double lo = 0.02, double hi = 0.98) {
  return {test::uniform(lo, hi), test::uniform(lo, hi), test::uniform(lo, hi)};
}

std::vector<PointMatch> samplesThrough(const Transform& f, int count, double noise = 0.0) {
  std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
  std::vector<PointMatch> out;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d c = randomColour();
    Eigen::Vector3d d = f(c);
    if (noise > 0)
      for (int i = 0; i < 3; ++i) d[i] += gauss(test::rng());
    out.push_back({c, d, true});
  }
  return out;
}

const Eigen::Matrix3d kMixing = (Eigen::Matrix3d() << 0.82, 0.12, 0.03,  //
                                 0.05, 0.90, 0.07,                       //
                                 0.02, 0.15, 0.78)
                                    .finished();
const Eigen::Vector3d kOffset(0.04, 0.02, 0.06);

Eigen::Vector3d linearTruth(const Eigen::Vector3d& c) { return kMixing * c; }
Eigen::Vector3d affineTruth(const Eigen::Vector3d& c) { return kMixing * c + kOffset; }
// A rational quadratic: highlights stay near white while mid-tones shift (the paper's Fig 6).
Eigen::Vector3d rationalTruth(const Eigen::Vector3d& c) {
  const double w = 1.0 + 0.6 * c.squaredNorm() - 0.3 * c.x() * c.z();
  Eigen::Vector3d n;
  n.x() = 0.9 * c.x() + 0.4 * c.x() * c.x() + 0.2 * c.y() * c.z() + 0.05;
  n.y() = 0.3 * c.y() + 1.1 * c.y() * c.y() + 0.2 * c.x() * c.y();
  n.z() = 0.5 * c.z() + 0.8 * c.z() * c.z() + 0.3 * c.x() * c.x() + 0.1;
  return n / w;
}
// Root-polynomial (Finlayson et al. 2015, degree 2): exactly in that model's span.
Eigen::Vector3d rootPolynomialTruth(const Eigen::Vector3d& c) {
  Eigen::Matrix<double, 3, 6> m;
  m << 0.6, 0.0, 0.0, 0.5, 0.0, 0.3,  //
      0.0, 0.5, 0.0, 0.4, 0.4, 0.0,   //
      0.0, 0.0, 0.6, 0.0, 0.3, 0.4;
  return m * colourTerms(ColourModel::RootPolynomial, c);
}

// Mean ΔE00 between a fitted map and the truth over a 9³ grid of the unit cube's interior.
double gridDeltaE(const ColourMap& map, const Transform& truth, double* max_de = nullptr) {
  double sum = 0.0, worst = 0.0;
  int n = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k, ++n) {
        const Eigen::Vector3d c(0.05 + 0.1125 * i, 0.05 + 0.1125 * j, 0.05 + 0.1125 * k);
        const auto y = map.apply(c);
        const double de = y ? deltaE2000(truth(c), *y) : 1e9;
        sum += de;
        worst = std::max(worst, de);
      }
  if (max_de) *max_de = worst;
  return sum / n;
}

// The camera's colour output for an opaque colour, through Camera::evaluate (eq 3, 5).
Eigen::Vector4d cameraColour(const Camera& camera, const Eigen::Vector3d& rgb) {
  Eigen::VectorXd x(7);
  x << 0.3, -0.2, 1.0, rgb.x(), rgb.y(), rgb.z(), 1.0;
  const Eigen::VectorXd y = camera.evaluate(x);
  return y.segment<4>(3);
}

ColourFitSummary fit(const std::vector<PointMatch>& samples, ColourModel model) {
  ColourFitOptions o;
  o.model = model;
  return fitColourSamples(samples, o);
}

}  // namespace

class TestFitColour : public QObject {
  Q_OBJECT

 private slots:
  void exactSamplesRecoverEachModel() {
    const struct {
      ColourModel model;
      Transform truth;
      int samples;
    } cases[] = {{ColourModel::Linear, linearTruth, 3},
                 {ColourModel::Affine, affineTruth, 4},
                 {ColourModel::RootPolynomial, rootPolynomialTruth, 6},
                 {ColourModel::Quadratic, rationalTruth, 13},
                 {ColourModel::Quadratic, rationalTruth, 40}};
    for (const auto& c : cases) {
      const ColourFitSummary s = fit(samplesThrough(c.truth, c.samples), c.model);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      QCOMPARE(s.map.model, c.model);
      double worst = 0.0;
      const double mean_de = gridDeltaE(s.map, c.truth, &worst);
      QVERIFY2(worst < 1e-6, qPrintable(QString("%1 from %2 samples: grid mean %3, max %4")
                                            .arg(colourModelName(c.model).data())
                                            .arg(c.samples).arg(mean_de).arg(worst)));
      QVERIFY(s.max_de < 1e-6);
    }
  }

  void linearCoefficientsFromNoisySamples() {
    // σ = 0.002 per channel over 60 samples: the least-squares matrix is within a few
    // standard errors (σ / (√60 · RMS colour) ≈ 5e-4) of the truth.
    const ColourFitSummary s = fit(samplesThrough(linearTruth, 60, 0.002), ColourModel::Linear);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    const double err = (s.map.m - kMixing).cwiseAbs().maxCoeff();
    QVERIFY2(err < 4e-3, qPrintable(QString("max coefficient error %1").arg(err)));
    // The held-out error stays close to the training error: no overfitting at 9 parameters.
    QVERIFY(s.held_out_de > 0.0 && s.held_out_de < 1.5 * s.mean_de + 0.05);
  }

  void autoPicksTheSimplestAdequateModel() {
    const struct {
      Transform truth;
      ColourModel expected;
    } cases[] = {{linearTruth, ColourModel::Linear},
                 {affineTruth, ColourModel::Affine},
                 {rationalTruth, ColourModel::Quadratic}};
    for (const auto& c : cases) {
      const ColourFitSummary s = fit(samplesThrough(c.truth, 80, 0.001), ColourModel::Auto);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      QVERIFY2(s.map.model == c.expected && s.selected == c.expected,
               qPrintable(QString::fromStdString(s.reason)));
      QCOMPARE(s.candidates.size(), size_t(4));
      // Recovered to what σ = 0.001 allows (about 0.1–0.3 dE00 in dark colours).
      QVERIFY2(gridDeltaE(s.map, c.truth) < 0.5, qPrintable(QString::fromStdString(s.report())));
    }
  }

  void rootPolynomialWinsButIsNeverStored() {
    const ColourFitSummary s = fit(samplesThrough(rootPolynomialTruth, 80, 0.0005), ColourModel::Auto);
    QVERIFY2(s.status.ok, s.status.message.c_str());
    QCOMPARE(s.selected, ColourModel::RootPolynomial);
    QVERIFY(s.map.model != ColourModel::RootPolynomial && s.stored);
    QVERIFY(s.reason.find("not a quadratic form") != std::string::npos);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, colourCamera(fit(samplesThrough(rootPolynomialTruth, 10),
                                                                     ColourModel::RootPolynomial).map,
                                                                 FrameSize{8, 8}));
  }

  void cameraAppliesTheMapThroughTheColourBlock() {
    for (ColourModel model : {ColourModel::Linear, ColourModel::Affine, ColourModel::Quadratic}) {
      const Transform truth = model == ColourModel::Quadratic ? Transform(rationalTruth)
                              : model == ColourModel::Affine  ? Transform(affineTruth)
                                                              : Transform(linearTruth);
      const ColourFitSummary s = fit(samplesThrough(truth, 30), model);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      const Camera camera = colourCamera(s.map, FrameSize{640, 480});
      const CameraStructure st = analyseStructure(camera);
      QCOMPARE(st.geometry, GeometryClass::Identity);  // the renderer's colour-only path
      QVERIFY(!st.geometry_depends_on_attributes && st.attributes_change);
      for (int t = 0; t < 50; ++t) {
        const Eigen::Vector3d c = randomColour(0.0, 1.0);
        const Eigen::Vector4d y = cameraColour(camera, c);
        QVERIFY2((y.head<3>() - truth(c)).norm() < 1e-7, colourModelName(model).data());
        QCOMPARE(y[3], 1.0);  // opaque stays opaque
      }
    }
  }

  // End to end: the camera written for a fitted map recolours an image through the renderer's
  // colour-only path (no resampling), each pixel to the true map's colour (float precision),
  // opaque pixels staying opaque.
  void renderedImageFollowsTheTrueMap() {
    for (ColourModel model : {ColourModel::Affine, ColourModel::Quadratic}) {
      const Transform truth = model == ColourModel::Quadratic ? Transform(rationalTruth)
                                                              : Transform(affineTruth);
      const ColourFitSummary s = fit(samplesThrough(truth, 40), model);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      const int w = 24, h = 16;
      ImageF photo(w, h, 3);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          float* p = photo.pixel(x, y);
          p[0] = static_cast<float>(x) / (w - 1);
          p[1] = static_cast<float>(y) / (h - 1);
          p[2] = static_cast<float>((x + y) % 7) / 6.0f;
        }
      AttributedSummary summary;
      const AttributedImage out =
          renderAttributed(photo, nullptr, colourCamera(s.map, FrameSize{w, h}), {}, &summary);
      QCOMPARE(summary.path, AttributedPath::ColourOnly);
      QCOMPARE(out.colour.width, w);
      QCOMPARE(out.colour.height, h);
      double worst = 0.0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const float* in = photo.pixel(x, y);
          const float* o = out.colour.pixel(x, y);
          const Eigen::Vector3d expected = truth(Eigen::Vector3d(in[0], in[1], in[2]));
          QCOMPARE(o[3], 1.0f);
          for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(o[c] - expected[c]));
        }
      QVERIFY2(worst < 1e-5, qPrintable(QString("%1: worst channel error %2")
                                            .arg(colourModelName(model).data()).arg(worst)));
    }
  }

  void robustFitRejectsOutliers() {
    std::vector<PointMatch> samples = samplesThrough(affineTruth, 100, 0.001);
    std::vector<bool> outlier(samples.size(), false);
    for (size_t k = 0; k < samples.size(); k += 4) {  // 25 %: a wrong patch picked
      samples[k].target = randomColour();
      outlier[k] = deltaE2000(samples[k].target, affineTruth(samples[k].source)) > 6.0;
    }
    ColourFitOptions o;
    o.robust = true;
    const ColourFitSummary robust = fitColourSamples(samples, o);
    QVERIFY2(robust.status.ok, robust.status.message.c_str());
    for (int k : robust.inliers) QVERIFY2(!outlier[k], qPrintable(QString("outlier %1 kept").arg(k)));
    QVERIFY(robust.inliers.size() >= 70);
    const double robust_error = gridDeltaE(robust.map, affineTruth);
    QVERIFY2(robust_error < 0.3, qPrintable(QString::fromStdString(robust.report())));
    // Without the robust option the outliers pull the map far off: the test can fail.
    const ColourFitSummary plain = fit(samples, ColourModel::Auto);
    QVERIFY(plain.status.ok);
    QVERIFY(gridDeltaE(plain.map, affineTruth) > 5.0 * robust_error);
  }

  void refusalsNameTheCause() {
    const auto message = [](const std::vector<PointMatch>& samples, ColourModel model) {
      return fit(samples, model).status.message;
    };
    const std::string few = message(samplesThrough(affineTruth, 2), ColourModel::Linear);
    QVERIFY2(few.find("needs at least 3") != std::string::npos &&
                 few.find("1 more sample") != std::string::npos, few.c_str());
    std::vector<PointMatch> grey;
    for (int k = 0; k < 20; ++k) {
      const double v = 0.05 * (k + 1);
      grey.push_back({Eigen::Vector3d(v, v, v), Eigen::Vector3d(v, 0.9 * v, 0.8 * v), true});
    }
    const std::string flat = message(grey, ColourModel::Affine);
    QVERIFY2(flat.find("too alike") != std::string::npos, flat.c_str());
    auto bad = samplesThrough(affineTruth, 10);
    bad[4].target[1] = std::nan("");
    QVERIFY2(message(bad, ColourModel::Auto).find("sample 5 has a non-finite value") != std::string::npos,
             message(bad, ColourModel::Auto).c_str());
    QVERIFY(message({}, ColourModel::Auto).find("no enabled colour samples") != std::string::npos);
  }

  // The exact extremes of a quadratic over a box (27 stationary-point solves) bracket and
  // match dense sampling: sampling can only find values inside the exact range, and gets
  // close to both ends.
  void quadraticRangeAgreesWithDenseSampling() {
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::Matrix4d q;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) q(r, c) = test::uniform(-1, 1);
      const Eigen::Vector3d lo(test::uniform(-1, 0), test::uniform(-1, 0), test::uniform(-1, 0));
      const Eigen::Vector3d hi = lo + Eigen::Vector3d(test::uniform(0.5, 2), test::uniform(0.5, 2),
                                                      test::uniform(0.5, 2));
      const QuadraticRange exact = quadraticRangeOverBox(q, lo, hi);
      double least = std::numeric_limits<double>::infinity(), greatest = -least;
      const int n = 40;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
          for (int k = 0; k <= n; ++k) {
            const Eigen::Vector3d x = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(i, j, k) / n);
            const Eigen::Vector4d c(x.x(), x.y(), x.z(), 1.0);
            const double v = c.dot(q * c);
            least = std::min(least, v);
            greatest = std::max(greatest, v);
          }
      const double span = std::max(1.0, exact.greatest - exact.least);
      QVERIFY(exact.least <= least + 1e-12 && exact.greatest >= greatest - 1e-12);
      QVERIFY2(least - exact.least < 2e-3 * span && exact.greatest - greatest < 2e-3 * span,
               qPrintable(QString("exact [%1, %2], sampled [%3, %4]")
                              .arg(exact.least).arg(exact.greatest).arg(least).arg(greatest)));
    }
  }

  void perSampleDeltaEIsReported() {
    auto samples = samplesThrough(affineTruth, 12);
    samples[3].target += Eigen::Vector3d(0.05, 0.0, 0.0);
    const ColourFitSummary s = fit(samples, ColourModel::Affine);
    QVERIFY(s.status.ok);
    QCOMPARE(s.delta_e.size(), samples.size());
    for (size_t k = 0; k < samples.size(); ++k)
      QVERIFY(std::abs(s.delta_e[k] - deltaE2000(samples[k].target, *s.map.apply(samples[k].source))) < 1e-12);
    QCOMPARE(s.max_de, *std::max_element(s.delta_e.begin(), s.delta_e.end()));
    QVERIFY(s.median_de <= s.max_de && s.mean_de <= s.max_de);
  }
};

QTEST_GUILESS_MAIN(TestFitColour)
#include "test_fit_colour.moc"
