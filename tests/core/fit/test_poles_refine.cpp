// SPDX-License-Identifier: Apache-2.0
// Poles over the frame (exact, checked against dense sampling), LM refinement guarantees, and
// real lens distortions (the models lensfun documents: poly3, poly5, ptlens) in both directions.
#include "core/fit/fit_image.h"
#include "core/fit/poles.h"
#include "core/model/frames.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <functional>

using namespace artcam;

namespace {

const FrameSize kFrame{600, 400};

// Radial models in lensfun's convention: r measured in units of half the shorter side.
using Radial = std::function<double(double)>;
Radial poly3(double k1) { return [=](double r) { return r * (1 - k1 + k1 * r * r); }; }
Radial poly5(double k1, double k2) {
  return [=](double r) { return r * (1 + k1 * r * r + k2 * r * r * r * r); };
}
Radial ptlens(double a, double b, double c) {
  return [=](double r) { return r * (a * r * r * r + b * r * r + c * r + 1 - a - b - c); };
}

Eigen::Vector2d applyRadial(const Radial& f, const Eigen::Vector2d& pixel) {
  const Eigen::Vector2d centre(kFrame.width / 2.0, kFrame.height / 2.0);
  const double unit = std::min(kFrame.width, kFrame.height) / 2.0;
  const Eigen::Vector2d d = (pixel - centre) / unit;
  const double r = d.norm();
  return r == 0.0 ? pixel : centre + d * (f(r) / r) * unit;
}

// The inverse radial map by Newton on r (the "other direction" of each lens).
Radial inverted(const Radial& f) {
  return [=](double rd) {
    double r = rd;
    for (int i = 0; i < 50; ++i) {
      const double h = 1e-7;
      const double g = (f(r + h) - f(r - h)) / (2 * h);
      r -= (f(r) - rd) / g;
    }
    return r;
  };
}

std::vector<PointMatch> lensMatches(const Radial& f) {
  std::vector<PointMatch> m;
  for (int j = 0; j <= 14; ++j)
    for (int i = 0; i <= 20; ++i) {
      const Eigen::Vector2d s(kFrame.width * i / 20.0, kFrame.height * j / 14.0);
      m.push_back({s, applyRadial(f, s), true});
    }
  return m;
}

}  // namespace

class TestPolesRefine : public QObject {
  Q_OBJECT

 private slots:
  // The exact check agrees with dense sampling: a sign change seen by sampling is always a
  // pole, and a pole-free verdict never meets a sampled sign change.
  void exactPoleCheckAgreesWithSampling() {
    int poles = 0, free = 0;
    for (int t = 0; t < 300; ++t) {
      Eigen::Matrix3d q;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) q(r, c) = test::uniform(-1, 1);
      q = 0.5 * (q + q.transpose()).eval();
      const PoleCheck check = checkDenominator(q, {-1, -0.7}, {1, 0.7});
      bool pos = false, neg = false;
      for (int j = 0; j <= 200; ++j)
        for (int i = 0; i <= 200; ++i) {
          const Eigen::Vector3d x(-1 + 2.0 * i / 200, -0.7 + 1.4 * j / 200, 1.0);
          const double d = x.dot(q * x);
          pos |= d > 0;
          neg |= d < 0;
        }
      if (pos && neg) QVERIFY2(!check.pole_free, "sampling found a sign change the check missed");
      if (check.pole_free) QVERIFY(!(pos && neg));
      (check.pole_free ? free : poles) += 1;
    }
    QVERIFY(poles > 20 && free > 20);  // both verdicts exercised
  }

  // A saddle whose zero lines only graze the frame between sample points is still found.
  void thinCrossingIsFound() {
    Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
    q(0, 0) = 1.0;   // u² - 1e-6·(…) : dips below zero only on a hair-thin band at u = 0
    q(2, 2) = -1e-8;
    QVERIFY(!checkDenominator(q, {-1, -1}, {1, 1}).pole_free);
    q(2, 2) = 1e-8;
    QVERIFY(checkDenominator(q, {-1, -1}, {1, 1}).pole_free);
  }

  void refinementNeverEndsWorseThanTheAlgebraicFit() {
    for (int trial = 0; trial < 5; ++trial) {
      const Camera truth = test::randomRationalCamera(kFrame, kFrame, 0.1);
      std::vector<PointMatch> m;
      std::normal_distribution<double> noise(0.0, 1.0);
      for (int k = 0; k < 60; ++k) {
        const Eigen::Vector2d s(test::uniform(0, 600), test::uniform(0, 400));
        m.push_back({s, *targetPixelFromSourcePixel(truth, s) +
                            Eigen::Vector2d(noise(test::rng()), noise(test::rng())), true});
      }
      FitOptions o;
      o.model = ModelClass::Quadratic;
      const FitSummary s = fitImageCamera(m, kFrame, kFrame, o);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      QVERIFY(s.record.algebraic_rms_px > 0);
      QVERIFY2(s.record.rms_px <= s.record.algebraic_rms_px * (1 + 1e-12), s.report().c_str());
      QVERIFY(s.record.pole_free);
    }
  }

  // Nine clicked pairs with 0.5 px noise leave one redundant equation: LM could fit them to a
  // few hundredths of a pixel by parking the pole curve on a frame corner (margin ~1e-11, the
  // map 1e10 px off there). The pairs below are such a case (a mild lens, 6000×4000; the
  // algebraic fit has a pole, LM from the affine fit used to end at margin 1.3e-11): the floor
  // of RefineOptions::min_pole_margin must hold it at 1e-3. Random sets must respect it too.
  void fewNoisyMatchesKeepAPoleMargin() {
    const FrameSize frame{6000, 4000};
    const double pairs[9][4] = {{5549.191509755671, 3794.4231119727087, 5786.852256316742, 3893.5116404661076},
                                {3552.1633613144118, 1694.9896329398455, 3546.444326917186, 1696.1022465148997},
                                {1151.9829452357562, 1778.294295492052, 1052.3024010567597, 1765.8247725486074},
                                {148.60180493741115, 343.0963451050046, -186.1744457776414, 84.67880004183546},
                                {3075.803546354136, 2936.836315133982, 3077.646947661041, 2943.423462768585},
                                {4698.614136963025, 2356.4939310880195, 4717.436186211436, 2357.3886981245037},
                                {5824.411365473743, 1451.1700739124337, 5897.540084693981, 1430.2382364651357},
                                {3432.280687150685, 2642.1284370012722, 3437.557454108696, 2642.042201466646},
                                {2844.398536278236, 2871.6560150111964, 2839.782417972726, 2879.3172308189605}};
    std::vector<PointMatch> fixed;
    for (const auto& p : pairs)
      fixed.push_back({Eigen::Vector2d(p[0], p[1]), Eigen::Vector2d(p[2], p[3]), true});
    FitOptions o;
    o.model = ModelClass::Quadratic;
    const FitSummary f = fitImageCamera(fixed, frame, frame, o);
    QVERIFY2(f.status.ok, f.status.message.c_str());
    QVERIFY2(f.record.pole_margin >= 1e-3 * (1 - 1e-9), qPrintable(QString::number(f.record.pole_margin)));
    QVERIFY(f.record.rms_px < 1.0);  // still fits the clicks

    Camera truth = Camera::identity({Block{BlockKind::Position, 3}}, frame, frame);
    truth.stages()[0].q[2](0, 0) = truth.stages()[0].q[2](1, 1) = -0.08;
    truth.stages()[0].q[2](0, 2) = truth.stages()[0].q[2](2, 0) = 0.02;
    truth.stages()[0].q[0](0, 1) = truth.stages()[0].q[0](1, 0) = 0.03;
    std::normal_distribution<double> noise(0.0, 0.5);
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<PointMatch> m;
      for (int k = 0; k < 9; ++k) {
        const Eigen::Vector2d s(test::uniform(0, 6000), test::uniform(0, 4000));
        m.push_back({s, *targetPixelFromSourcePixel(truth, s) +
                            Eigen::Vector2d(noise(test::rng()), noise(test::rng())), true});
      }
      const FitSummary s = fitImageCamera(m, frame, frame, o);
      if (s.status) QVERIFY2(s.record.pole_margin >= 1e-3 * (1 - 1e-9), s.report().c_str());
    }
  }

  // Real lens distortions, both directions. The rational quadratic cannot represent a radial
  // polynomial exactly; the fit must be pole-free and the refined error below the algebraic.
  void realLensDistortionsFitPoleFree_data() {
    QTest::addColumn<double>("a");
    QTest::addColumn<double>("b");
    QTest::addColumn<double>("c");
    QTest::addColumn<int>("model");  // 0 poly3, 1 poly5, 2 ptlens
    QTest::addColumn<double>("max_rms_px");
    QTest::newRow("poly3 barrel") << -0.02 << 0.0 << 0.0 << 0 << 1.0;
    QTest::newRow("poly3 pincushion") << 0.015 << 0.0 << 0.0 << 0 << 1.0;
    QTest::newRow("poly5 mustache") << -0.08 << 0.03 << 0.0 << 1 << 5.0;  // the model is the limit here
    QTest::newRow("ptlens wide angle") << 0.01 << -0.04 << 0.0 << 2 << 3.0;
  }
  void realLensDistortionsFitPoleFree() {
    QFETCH(double, a);
    QFETCH(double, b);
    QFETCH(double, c);
    QFETCH(int, model);
    QFETCH(double, max_rms_px);
    const Radial f = model == 0 ? poly3(a) : model == 1 ? poly5(a, b) : ptlens(a, b, c);
    for (const Radial& direction : {f, inverted(f)}) {
      FitOptions o;
      o.model = ModelClass::Quadratic;
      const FitSummary s = fitImageCamera(lensMatches(direction), kFrame, kFrame, o);
      QVERIFY2(s.status.ok, s.status.message.c_str());
      QVERIFY(s.record.pole_free);
      QVERIFY(checkPoles(s.camera).pole_free);
      QVERIFY2(s.record.rms_px <= s.record.algebraic_rms_px * (1 + 1e-12), s.report().c_str());
      qInfo("%s: algebraic RMS %.4f px, refined %.4f px, max %.4f px, pole margin %.3g %s",
            QTest::currentDataTag(), s.record.algebraic_rms_px, s.record.rms_px, s.record.max_px,
            s.record.pole_margin, s.record.reason.c_str());
      QVERIFY2(s.record.rms_px < max_rms_px, s.report().c_str());
    }
  }
};

QTEST_GUILESS_MAIN(TestPolesRefine)
#include "test_poles_refine.moc"
