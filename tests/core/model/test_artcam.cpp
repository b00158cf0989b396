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
    // Aerial perspective outputs a log depth; depth of field would read it as a depth.
    const Artcam aerial(aerialPerspectiveCamera({}, kFrame, kFrame));
    Artcam dof(depthOfFieldCamera({2.0, 0.01}, kFrame, kFrame));
    dof.depth_output = DepthOutput::BlurVariance;
    const auto refused = composeArtcams(aerial, dof);
    QVERIFY(!refused.ok());
    QVERIFY(refused.status.message.find("depth") != std::string::npos);
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
