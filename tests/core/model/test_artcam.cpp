// SPDX-License-Identifier: Apache-2.0
// The camera value (core/model/artcam.h): its kind and its invariants, checked by
// validateArtcam on read, write and render. Each refusal names the part at fault.
#include "core/io/artcam_file.h"
#include "core/model/artcam.h"
#include "core/model/compose.h"
#include "core/effects/aerial.h"
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

const FrameSize kFrame{600, 400};

Artcam piecewiseOf(int patches) {
  Artcam camera(test::randomHomographyCamera(kFrame, kFrame));
  PiecewiseCamera pieces;
  pieces.source_size = pieces.target_size = kFrame;
  const double w = static_cast<double>(kFrame.width) / patches;
  for (int i = 0; i < patches; ++i) {
    CameraPatch patch;
    patch.rect = {i * w, 0.0, (i + 1) * w, double(kFrame.height)};
    patch.camera = test::randomHomographyCamera(kFrame, kFrame);
    pieces.patches.push_back(patch);
  }
  camera.pieces = pieces;
  return camera;
}

bool refusedWith(const Artcam& camera, const std::string& text) {
  const Status s = validateArtcam(camera);
  if (s.ok || s.message.find(text) == std::string::npos) {
    qWarning("expected a refusal with \"%s\", got \"%s\"", text.c_str(), s.message.c_str());
    return false;
  }
  // The reader refuses the same file with the file's name in front.
  const auto read = parseArtcam(toArtcamJson(camera), "x.artcam");
  return !read.ok() && read.status.message.rfind("x.artcam: ", 0) == 0 &&
         read.status.message.find(text) != std::string::npos;
}

}  // namespace

class TestArtcam : public QObject {
  Q_OBJECT

 private slots:
  void kinds() {
    QCOMPARE(Artcam(test::randomRationalCamera(kFrame, kFrame)).kind(), ArtcamKind::Single);
    auto chain = composeCameras(test::randomRationalCamera(kFrame, kFrame),
                                test::randomRationalCamera(kFrame, kFrame));
    QVERIFY(chain.ok());
    QCOMPARE(Artcam(*chain).kind(), ArtcamKind::Chained);
    Artcam layered;
    layered.layers = rgbShiftLayers({}, kFrame, kFrame);
    QCOMPARE(layered.kind(), ArtcamKind::Layered);
    QCOMPARE(Artcam(aerialPerspectiveCamera({}, kFrame, kFrame)).kind(), ArtcamKind::Attributed);
    QCOMPARE(piecewiseOf(3).kind(), ArtcamKind::Piecewise);
    QVERIFY(validateArtcam(piecewiseOf(3)).ok);
    QVERIFY(validateArtcam(layered).ok);
  }

  void refusesBrokenPatches() {
    Artcam overlap = piecewiseOf(3);
    overlap.pieces->patches[2].rect.x0 -= 50.0;  // into patch 1
    QVERIFY(refusedWith(overlap, "/patches/2/rect: overlaps patch 1"));

    Artcam inverted = piecewiseOf(2);
    std::swap(inverted.pieces->patches[1].rect.x0, inverted.pieces->patches[1].rect.x1);
    QVERIFY(refusedWith(inverted, "/patches/1/rect: x1 must exceed x0"));

    Artcam outside = piecewiseOf(2);
    outside.pieces->patches[1].rect.x1 = 5000.0;
    QVERIFY(refusedWith(outside, "/patches/1/rect: outside the 600x400 source frame"));

    Artcam zero = piecewiseOf(2);
    for (Eigen::MatrixXd& q : zero.pieces->patches[0].camera.stages()[0].q) q.setZero();
    QVERIFY(refusedWith(zero, "/patches/0/camera: every tensor of a stage is zero"));

    Artcam none = piecewiseOf(1);
    none.pieces->patches.clear();
    QVERIFY(!validateArtcam(none).ok);

    Artcam many = piecewiseOf(kMaxPatches + 1);
    QVERIFY(refusedWith(many, "more than the 1024 allowed"));

    Artcam layered_patches = piecewiseOf(2);
    layered_patches.layers.push_back(layered_patches.main());
    QVERIFY(!validateArtcam(layered_patches).ok);
  }

  void refusesZeroAndMismatchedLayers() {
    Artcam zero(test::randomRationalCamera(kFrame, kFrame));
    for (Eigen::MatrixXd& q : zero.main().stages()[0].q) q.setZero();
    QVERIFY(refusedWith(zero, "/stages: every tensor of a stage is zero"));

    Artcam mismatched;
    mismatched.layers = rgbShiftLayers({}, kFrame, kFrame);
    mismatched.layers[2].setFrames(kFrame, {300, 200});
    QVERIFY(!validateArtcam(mismatched).ok);

    Artcam no_depth(test::randomRationalCamera(kFrame, kFrame));
    no_depth.depth_output = DepthOutput::BlurVariance;
    QVERIFY(refusedWith(no_depth, "/depth_output"));
  }

  void patchesRoundTripExactly() {
    const Artcam original = piecewiseOf(4);
    const auto read = parseArtcam(toArtcamJson(original), "pw.artcam");
    QVERIFY2(read.ok(), read.status.message.c_str());
    QVERIFY(read->pieces);
    QCOMPARE(read->pieces->patches.size(), size_t{4});
    for (size_t i = 0; i < 4; ++i) {
      QCOMPARE(read->pieces->patches[i].rect.x0, original.pieces->patches[i].rect.x0);
      for (size_t k = 0; k < 3; ++k)
        QVERIFY(read->pieces->patches[i].camera.stages()[0].q[k] ==
                original.pieces->patches[i].camera.stages()[0].q[k]);
    }
    QCOMPARE(toArtcamJson(*read), toArtcamJson(original));
  }

  void composeLayerByLayerAndRefusesWrongDepth() {
    Artcam ca;
    ca.layers = rgbShiftLayers({}, kFrame, kFrame);
    std::string text;
    const auto twice = composeArtcams(ca, ca, &text);
    QVERIFY2(twice.ok(), twice.status.message.c_str());
    QCOMPARE(twice->layers.size(), size_t{3});
    // Each composed layer is its layer applied twice (independent: the closed composition of
    // the two single cameras).
    for (size_t l = 0; l < 3; ++l) {
      const auto expected = composeCameras(ca.layers[l], ca.layers[l]);
      QVERIFY(expected.ok());
      const Eigen::VectorXd x = (Eigen::VectorXd(7) << 0.3, -0.2, 1, 0.2, 0.5, 0.7, 1).finished();
      QVERIFY((twice->layers[l].evaluate(x) - expected->evaluate(x)).norm() < 1e-12);
    }
    // Aerial perspective outputs a log depth: a fitted inverse depth bridges it to depth of
    // field's σ², so the paper's Fig 3 bottom right is one camera. Against the closed forms at
    // depths across the aerial range: colour exactly aerial perspective's, σ² = k²(d − f)²/d²
    // within 1 % of its largest value.
    AerialParams ap;
    ap.near = 1.0;
    ap.far = 50.0;
    const Artcam aerial(aerialPerspectiveCamera(ap, kFrame, kFrame));
    const double focus = 4.0, blur = 0.02;
    Artcam dof(depthOfFieldCamera({focus, blur}, kFrame, kFrame));
    dof.depth_output = DepthOutput::BlurVariance;
    std::string note;
    const auto fig3 = composeArtcams(aerial, dof, &note);
    QVERIFY2(fig3.ok(), fig3.status.message.c_str());
    QCOMPARE(fig3->depth_output, DepthOutput::BlurVariance);
    QVERIFY(note.find("bridged") != std::string::npos);
    double largest = 0, worst = 0;
    for (int j = 0; j <= 40; ++j) {
      const double d = ap.near * std::pow(ap.far / ap.near, j / 40.0);
      Eigen::VectorXd x(9);
      x << 0.2, -0.1, 1, 0.3 * 0.8, 0.5 * 0.8, 0.7 * 0.8, 0.8, d, 1;
      const Eigen::VectorXd composed = fig3->main().evaluate(x);
      const Eigen::VectorXd hazed = aerial.main().evaluate(x);
      QVERIFY((composed.segment(3, 4) - hazed.segment(3, 4)).norm() < 1e-9);
      const double sigma2 = blur * blur * (d - focus) * (d - focus) / (d * d);
      largest = std::max(largest, sigma2);
      worst = std::max(worst, std::abs(composed(7) - sigma2));
    }
    QVERIFY2(worst <= 0.01 * largest, qPrintable(QString("σ² off by %1 of %2").arg(worst).arg(largest)));
    // Aerial perspective twice: the second reads depth in its colour too, which no re-fit of a
    // depth output carries: refused, saying why.
    const auto twice_aerial = composeArtcams(aerial, aerial);
    QVERIFY(!twice_aerial.ok());
    QVERIFY(twice_aerial.status.message.find("depth") != std::string::npos);
    // Depth of field first: its output is no depth at all.
    QVERIFY(!composeArtcams(dof, aerial).ok());
    // A lens before depth of field passes depth on: composed, and the blur variance kept.
    const auto lens_then_dof = composeArtcams(Artcam(test::randomHomographyCamera(kFrame, kFrame)), dof);
    QVERIFY2(lens_then_dof.ok(), lens_then_dof.status.message.c_str());
    QCOMPARE(lens_then_dof->depth_output, DepthOutput::BlurVariance);
    // Unequal layer counts cannot pair up.
    Artcam two;
    two.layers = {ca.layers[0], ca.layers[1]};
    QVERIFY(!composeArtcams(ca, two).ok());
  }
};

QTEST_GUILESS_MAIN(TestArtcam)
#include "test_artcam.moc"
