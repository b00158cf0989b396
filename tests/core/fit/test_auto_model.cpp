// SPDX-License-Identifier: Apache-2.0
// Auto's choice of model (fit_image.cpp, chooseModel) against the map the pairs were made from:
// a few clicked pairs of a bulge give the quadratic camera (the paper's nine-point drawing,
// Fig 5), a noisy homography stays a homography, a shift stays a translation; with many
// matches of lens-like maps auto's error is within 2 % of the best model of the ladder.
#include "core/fit/fit_image.h"
#include "core/model/frames.h"

#include <Eigen/Geometry>
#include <QtTest/QtTest>

#include <cmath>
#include <functional>
#include <random>

using namespace artcam;

namespace {

const FrameSize kFrame{800, 600};
using Lens = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;  // pixel → pixel

// A map written in the normalised frame (centre 0, half the long side 1), as pixels.
Lens normalisedLens(std::function<Eigen::Vector2d(const Eigen::Vector2d&)> f) {
  return [f](const Eigen::Vector2d& p) {
    return pixelFromNormalized(kFrame, f(normalizedFromPixel(kFrame, p)));
  };
}

// The bulge u' = u / (1 − k r²): a quadratic camera with denominator 1 − k(u² + v²).
Lens bulge(double k) {
  return normalisedLens([k](const Eigen::Vector2d& u) { return Eigen::Vector2d(u / (1.0 - k * u.squaredNorm())); });
}

// No model of the ladder is exact: u' = u (1 + k1 r² + k2 r⁴).
Lens polynomialLens(double k1, double k2) {
  return normalisedLens([k1, k2](const Eigen::Vector2d& u) {
    const double r2 = u.squaredNorm();
    return Eigen::Vector2d(u * (1.0 + k1 * r2 + k2 * r2 * r2));
  });
}

Lens homographyLens(const Eigen::Matrix3d& h) {
  return normalisedLens([h](const Eigen::Vector2d& u) {
    const Eigen::Vector3d y = h * u.homogeneous();
    return Eigen::Vector2d(y.hnormalized());
  });
}

Eigen::Matrix3d mildPerspective() {
  Eigen::Matrix3d h;
  h << 1.03, 0.04, 0.02, -0.03, 0.98, -0.01, 0.06, -0.05, 1.0;
  return h;
}

// Pairs clicked on a jittered cols×rows grid over 10 %…90 % of the frame, the targets off by
// up to ±noise px in each coordinate (a click's precision).
std::vector<PointMatch> clickedPairs(const Lens& lens, int cols, int rows, double noise,
                                     std::mt19937_64& rng) {
  std::uniform_real_distribution<double> jitter(0.25, 0.75), click(-noise, noise);
  std::vector<PointMatch> out;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const Eigen::Vector2d s(kFrame.width * (0.1 + 0.8 * (i + jitter(rng)) / cols),
                              kFrame.height * (0.1 + 0.8 * (j + jitter(rng)) / rows));
      out.push_back({s, lens(s) + Eigen::Vector2d(click(rng), click(rng)), true});
    }
  return out;
}

// Many matches uniformly over the same region, Gaussian noise σ px.
std::vector<PointMatch> detectedMatches(const Lens& lens, int count, double sigma,
                                        std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(0.1 * kFrame.width, 0.9 * kFrame.width),
      y(0.1 * kFrame.height, 0.9 * kFrame.height);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<PointMatch> out;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d s(x(rng), y(rng));
    out.push_back({s, lens(s) + Eigen::Vector2d(noise(rng), noise(rng)), true});
  }
  return out;
}

FitSummary fit(const std::vector<PointMatch>& m, ModelClass model) {
  FitOptions o;
  o.model = model;
  return fitImageCamera(m, kFrame, kFrame, o);
}

// RMS distance (px) between a camera and the true map on a 30×30 grid over 15 %…85 % of the
// frame, inside where the pairs were made: the error a user sees, from the truth itself.
double trueError(const Camera& camera, const Lens& lens) {
  double sum = 0.0;
  int n = 0;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i, ++n) {
      const Eigen::Vector2d p(kFrame.width * (0.15 + 0.7 * i / 29.0),
                              kFrame.height * (0.15 + 0.7 * j / 29.0));
      const auto y = targetPixelFromSourcePixel(camera, p);
      if (!y) return std::numeric_limits<double>::infinity();
      sum += (*y - lens(p)).squaredNorm();
    }
  return std::sqrt(sum / n);
}

double largestDisplacement(const Lens& lens, const std::vector<PointMatch>& m) {
  double d = 0.0;
  for (const PointMatch& p : m) d = std::max(d, (lens(p.source) - p.source).norm());
  return d;
}

const ModelClass kLadder[] = {ModelClass::Translation, ModelClass::Similarity,
                              ModelClass::Affine, ModelClass::Homography, ModelClass::Quadratic};

}  // namespace

class TestAutoModel : public QObject {
  Q_OBJECT

 private slots:
  // (a) Nine or twelve clicked pairs of a bulge → the quadratic camera, close to the bulge.
  void clickedBulgePairsGiveTheQuadratic() {
    const Lens lens = bulge(0.1);
    for (const auto& [cols, rows] : {std::pair{3, 3}, std::pair{4, 3}})
      for (unsigned seed = 1; seed <= 5; ++seed) {
        std::mt19937_64 rng(seed);
        const auto pairs = clickedPairs(lens, cols, rows, 0.5, rng);
        QVERIFY(largestDisplacement(lens, pairs) > 10.0);
        const FitSummary s = fit(pairs, ModelClass::Auto);
        QVERIFY2(s.status.ok, s.status.message.c_str());
        QVERIFY2(s.record.model == "quadratic", s.record.reason.c_str());
        QCOMPARE(s.record.criterion, std::string("aic"));
        QVERIFY2(s.record.reason.find("auto chose quadratic") != std::string::npos,
                 s.record.reason.c_str());
        QVERIFY2(s.record.reason.find("information criterion") != std::string::npos,
                 s.record.reason.c_str());
        // The quadratic is closer to the bulge than the homography (nine noisy clicks leave
        // the exact fit 1–3 px off the bulge inside the pairs, the homography 4–9 px).
        const double quadratic = trueError(s.camera, lens);
        const double homography = trueError(fit(pairs, ModelClass::Homography).camera, lens);
        QVERIFY2(quadratic < homography,
                 qPrintable(QString("%1 pairs seed %2: quadratic %3 px, homography %4 px")
                                .arg(cols * rows).arg(seed).arg(quadratic).arg(homography)));
      }
  }

  // (b) A true homography with clicking noise stays a homography, not the quadratic.
  void noisyHomographyPairsStayAHomography() {
    const Lens lens = homographyLens(mildPerspective());
    for (const auto& [cols, rows] : {std::pair{3, 3}, std::pair{4, 3}, std::pair{4, 4}})
      for (unsigned seed = 1; seed <= 5; ++seed) {
        std::mt19937_64 rng(100 + seed);
        const FitSummary s = fit(clickedPairs(lens, cols, rows, 0.5, rng), ModelClass::Auto);
        QVERIFY2(s.status.ok, s.status.message.c_str());
        QVERIFY2(s.record.model == "homography", s.record.reason.c_str());
        QVERIFY(s.record.reason.find("auto chose homography") != std::string::npos);
      }
  }

  // (c) A pure shift stays a translation; a rotation and scale stays a similarity.
  void translationAndSimilarityStaySo() {
    const Lens shift = [](const Eigen::Vector2d& p) { return Eigen::Vector2d(p + Eigen::Vector2d(12.5, -7.25)); };
    const Lens turn = [](const Eigen::Vector2d& p) {
      const double a = 0.08, s = 1.04;
      const Eigen::Vector2d c(400, 300), d = p - c;
      return Eigen::Vector2d(c + s * Eigen::Vector2d(std::cos(a) * d.x() - std::sin(a) * d.y(),
                                                     std::sin(a) * d.x() + std::cos(a) * d.y()) +
                             Eigen::Vector2d(5, 3));
    };
    for (unsigned seed = 1; seed <= 5; ++seed) {
      std::mt19937_64 rng(200 + seed);
      for (const auto& [cols, rows] : {std::pair{3, 2}, std::pair{3, 3}, std::pair{4, 3}}) {
        const FitSummary t = fit(clickedPairs(shift, cols, rows, 0.5, rng), ModelClass::Auto);
        QVERIFY2(t.record.model == "translation", t.record.reason.c_str());
        const FitSummary s = fit(clickedPairs(turn, cols, rows, 0.5, rng), ModelClass::Auto);
        QVERIFY2(s.record.model == "similarity", s.record.reason.c_str());
      }
    }
  }

  // (d) Many matches of lens-like maps: auto's error against the true map is within 2 % of
  // the best model of the ladder (each fitted by name on the same matches).
  void manyMatchesStayWithinTwoPercentOfTheBest() {
    const std::pair<const char*, Lens> lenses[] = {
        {"radial bulge", bulge(0.1)},
        {"mild perspective", homographyLens(mildPerspective())},
        {"polynomial k1 r² + k2 r⁴", polynomialLens(0.04, 0.03)}};
    for (const auto& [name, lens] : lenses)
      for (int count : {50, 200}) {
        std::mt19937_64 rng(static_cast<unsigned>(count) + 7);
        const auto matches = detectedMatches(lens, count, 0.5, rng);
        const FitSummary automatic = fit(matches, ModelClass::Auto);
        QVERIFY2(automatic.status.ok, automatic.status.message.c_str());
        QCOMPARE(automatic.record.criterion, std::string("held-out"));
        double best = std::numeric_limits<double>::infinity();
        QString all;
        for (ModelClass model : kLadder) {
          const FitSummary s = fit(matches, model);
          if (!s.status.ok) continue;
          const double e = trueError(s.camera, lens);
          best = std::min(best, e);
          all += QString(" %1 %2").arg(QString::fromStdString(std::string(modelClassName(model)))).arg(e);
        }
        const double chosen = trueError(automatic.camera, lens);
        QVERIFY2(chosen <= 1.02 * best,
                 qPrintable(QString("%1, %2 matches: auto (%3) %4 px; models:%5")
                                .arg(name).arg(count)
                                .arg(QString::fromStdString(automatic.record.model))
                                .arg(chosen).arg(all)));
      }
  }

  // The per-model record: every rung of the ladder with its residual RMS (checked against the
  // model fitted by name), the criterion values, and the chosen model's own.
  // Matches that overflow every model's held-out error (a value of 1e300 reached the fit from
  // a caller that did not read it through the CSV reader) leave Auto without a judgeable model:
  // the fit says so instead of picking through a missing best (it crashed once).
  void overflowingMatchesPickNothingAndSaySo() {
    std::vector<PointMatch> m;
    for (int i = 0; i < 5; ++i)
      m.push_back({Eigen::Vector2d(10.0 + 40 * i, 10.0 + 15 * (i % 3)),
                   Eigen::Vector2d(11.0 + 40 * i, 12.0 + 15 * (i % 3)), true});
    m[3].target = Eigen::Vector2d(1e300, 99.0);
    const FitSummary fit = fitImageCamera(m, {200, 200}, {200, 200}, FitOptions{});
    QVERIFY(!fit.status.ok || std::isfinite(fit.record.rms_px));
    if (!fit.status.ok) QVERIFY(!fit.status.message.empty());
  }

  void theRecordListsEveryModel() {
    std::mt19937_64 rng(11);
    const auto pairs = clickedPairs(bulge(0.1), 3, 3, 0.5, rng);
    const FitSummary s = fit(pairs, ModelClass::Auto);
    QVERIFY(s.status.ok);
    QCOMPARE(s.record.models.size(), size_t{5});
    for (size_t k = 0; k < 5; ++k) {
      const ModelScore& m = s.record.models[k];
      QCOMPARE(m.model, std::string(modelClassName(kLadder[k])));
      const FitSummary named = fit(pairs, kLadder[k]);
      QVERIFY(named.status.ok);
      QVERIFY2(std::abs(m.rms_px - named.record.rms_px) < 1e-6 * (1 + named.record.rms_px),
               m.model.c_str());
      QVERIFY(m.criterion >= 0);
    }
    // Quadratic with nine pairs: held-out leaves eight, one fewer than it needs.
    QCOMPARE(s.record.models[4].held_out_rms_px, -1.0);
    QCOMPARE(s.record.rms_px, s.record.models[4].rms_px);
    // A model named by hand keeps the list, and says what auto would have chosen.
    const FitSummary h = fit(pairs, ModelClass::Homography);
    QCOMPARE(h.record.model, std::string("homography"));
    QCOMPARE(h.record.models.size(), size_t{5});
    QVERIFY2(h.record.reason.find("auto would choose quadratic") != std::string::npos,
             h.record.reason.c_str());
  }

  // Eight pairs cannot determine the quadratic: auto says so in the list and picks among the rest.
  void eightPairsNameWhatTheQuadraticNeeds() {
    std::mt19937_64 rng(12);
    auto pairs = clickedPairs(bulge(0.1), 3, 3, 0.5, rng);
    pairs.pop_back();
    const FitSummary s = fit(pairs, ModelClass::Auto);
    QVERIFY(s.status.ok);
    QVERIFY(s.record.model != "quadratic");
    QCOMPARE(s.record.models.back().rms_px, -1.0);
    QCOMPARE(s.record.models.back().note, std::string("needs 9 matches"));
  }
};

QTEST_APPLESS_MAIN(TestAutoModel)
#include "test_auto_model.moc"
