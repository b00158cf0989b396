// SPDX-License-Identifier: Apache-2.0
// Compositing as an ARTcam colour stage (core/colour/composite.h, the paper's eq 6/7): for random
// premultiplied colours A (the photo) and B (the second image) the camera's undivided output
// (eq 3) equals the Porter–Duff formula written out here from its definition, for every operator
// and amount, to 1e-12; the second colour passes through and the geometry is the identity. The
// effects table's composite row builds the same camera, and its operator is a named choice.
#include "core/colour/composite.h"
#include "core/effects/effect_table.h"
#include "core/model/structure.h"
#include "tests/support/porter_duff.h"

#include <QtTest/QtTest>

#include <Eigen/Core>

#include <random>
#include <stdexcept>

using namespace artcam;
using artcam::test::kCompositeOps;
using artcam::test::porterDuff;

namespace {

using Colour = Eigen::Vector4d;  // (a·r, a·g, a·b, a), premultiplied


Colour randomPremultiplied(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double alpha = unit(rng);
  return {alpha * unit(rng), alpha * unit(rng), alpha * unit(rng), alpha};
}

}  // namespace

class TestComposite : public QObject {
  Q_OBJECT

 private slots:
  void everyOperatorIsItsPorterDuffFormula() {
    std::mt19937 rng(20070329);
    std::uniform_real_distribution<double> position(-1.0, 1.0);
    const FrameSize frame{640, 480};
    std::vector<std::pair<Colour, Colour>> pairs;
    for (int i = 0; i < 200; ++i) pairs.emplace_back(randomPremultiplied(rng), randomPremultiplied(rng));
    // The ends of alpha: opaque over opaque, transparent either side.
    pairs.emplace_back(Colour(0.2, 0.3, 0.4, 1.0), Colour(0.9, 0.8, 0.7, 1.0));
    pairs.emplace_back(Colour(0, 0, 0, 0), Colour(0.5, 0.25, 0.125, 0.5));
    pairs.emplace_back(Colour(0.3, 0.1, 0.2, 0.6), Colour(0, 0, 0, 0));
    for (const CompositeOp op : kCompositeOps)
      for (const double t : {1.0, 0.37, 0.0}) {
        const Camera camera = compositeCamera(op, t, frame);
        for (const auto& [a, b] : pairs) {
          const double u = position(rng), v = position(rng);
          Eigen::VectorXd x(11);
          x << u, v, 1.0, a, b;
          const Eigen::VectorXd z = camera.evaluateHomogeneous(x);  // eq 3, undivided
          const Colour want = (1 - t) * a + t * porterDuff(op, a, b);
          const QString what = QString("%1 t=%2").arg(QString::fromUtf8(compositeOpName(op).data())).arg(t);
          QVERIFY2((z.segment<4>(3) - want).cwiseAbs().maxCoeff() < 1e-12, qPrintable(what));
          // Position and the second colour pass through (weight w = 1).
          QVERIFY2((z.head<3>() - Eigen::Vector3d(u, v, 1.0)).cwiseAbs().maxCoeff() < 1e-15,
                   qPrintable(what));
          QVERIFY2((z.segment<4>(7) - b).cwiseAbs().maxCoeff() < 1e-15, qPrintable(what));
        }
      }
  }

  // eq 5: the colour is divided by its weight, which becomes the output alpha clamped to [0, 1].
  // For over the weight is aA + aB − aA·aB ≤ 1, so the divided colour times alpha is the formula.
  void divisionKeepsAlphaAsWeight() {
    const Camera camera = compositeCamera(CompositeOp::Over, 1.0, {64, 48});
    const Colour a(0.1, 0.2, 0.05, 0.4), b(0.3, 0.6, 0.9, 0.9);
    Eigen::VectorXd x(11);
    x << 0.1, -0.2, 1.0, a, b;
    const Eigen::VectorXd y = camera.evaluate(x);
    const double alpha = 0.4 + 0.9 - 0.4 * 0.9;
    QVERIFY(std::abs(y[6] - alpha) < 1e-14);
    for (int k = 0; k < 3; ++k) QVERIFY(std::abs(y[3 + k] * alpha - (a[k] + 0.6 * b[k])) < 1e-14);
  }

  void geometryIsTheIdentityAndColourChanges() {
    const CameraStructure s = analyseStructure(compositeCamera(CompositeOp::Multiply, 0.5, {64, 48}));
    QVERIFY(s.geometry == GeometryClass::Identity);
    QVERIFY(!s.geometry_depends_on_attributes);
    QVERIFY(s.attributes_change);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, compositeCamera(CompositeOp::Over, 1.5, {64, 48}));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, compositeCamera(CompositeOp::Over, 1.0, {0, 0}));
  }

  void operatorNamesRoundTrip() {
    for (const CompositeOp op : kCompositeOps) QVERIFY(compositeOpFromName(compositeOpName(op)) == op);
    QVERIFY(!compositeOpFromName("overlay"));
    QCOMPARE(compositeOpNames().size(), std::size(kCompositeOps));
  }

  // The effects table's row: the operator is a named choice (its index is the value), and the
  // builder makes compositeCamera's camera for every operator.
  void effectRowBuildsTheCompositeCamera() {
    const EffectSpec* spec = findEffect("composite");
    QVERIFY(spec);
    QVERIFY(spec->needs_second && !spec->needs_depth);
    const EffectParam* op = findParam(*spec, "op");
    QVERIFY(op && op->isChoice());
    QCOMPARE(QString::fromStdString(defaultText(*op)), QString("over"));
    QCOMPARE(QString::fromStdString(rangeText(*op)),
             QString("over|under|in|out|atop|xor|add|multiply|screen|mix"));
    QVERIFY(choiceValue(*op, "screen") == 8.0);
    QVERIFY(choiceValue(*op, "3") == 3.0);
    QVERIFY(!choiceValue(*op, "overlay"));
    QVERIFY(!choiceValue(*op, "10"));
    QVERIFY(!checkEffectValue(*op, {2.5}).empty());
    QVERIFY(!checkEffectValue(*op, {10.0}).empty());
    QVERIFY(checkEffectValue(*op, {9.0}).empty());
    const FrameSize frame{320, 200};
    for (size_t i = 0; i < std::size(kCompositeOps); ++i) {
      const Artcam built = buildEffect("composite", {{"op", {double(i)}}, {"amount", {0.25}}}, frame);
      const Camera want = compositeCamera(kCompositeOps[i], 0.25, frame);
      QCOMPARE(built.layers.size(), size_t{1});
      QVERIFY(built.main().blocks() == want.blocks());
      for (size_t e = 0; e < want.stages()[0].q.size(); ++e)
        QVERIFY(built.main().stages()[0].q[e] == want.stages()[0].q[e]);
    }
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             buildEffect("composite", {{"op", {1.5}}}, frame));
  }
};

QTEST_GUILESS_MAIN(TestComposite)
#include "test_composite.moc"
