// SPDX-License-Identifier: Apache-2.0
// The document's whole camera (core/project/document_camera.h) and the export render
// (project_render.h), checked against independent truths: the composed camera maps points as
// the separate cameras applied one after the other do; an effect reading depth is left out,
// with the reason, only when there is no depth; crop and fill against hand-made images.
#include "core/effects/effect_table.h"
#include "core/project/document_camera.h"
#include "core/project/project_render.h"

#include <QtTest/QtTest>

using namespace artcam;

namespace {

const FrameSize kFrame{600, 400};

Eigen::Vector2d position(const Camera& c, const Eigen::Vector2d& p) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(c.dimension());
  x[0] = p.x();
  x[1] = p.y();
  x[2] = 1.0;
  // Colour and depth blocks (if any): an opaque grey at depth 2, homogeneous.
  const BlockLayout& l = c.layout();
  for (size_t b = 1; b < l.blocks.size(); ++b) {
    const int o = l.offsets[b];
    if (l.blocks[b].kind == BlockKind::Colour) x.segment(o, 4) << 0.5, 0.5, 0.5, 1.0;
    if (l.blocks[b].kind == BlockKind::Depth) x.segment(o, 2) << 2.0, 1.0;
  }
  return c.evaluate(x).head<2>();
}

}  // namespace

class TestDocumentCamera : public QObject {
  Q_OBJECT

 private slots:
  void effectsApplyAfterTheGeometryInOrder() {
    const Camera twist = buildEffect("twist", {{"rate", {0.2}}}, kFrame).main();
    const Camera barrel = buildEffect("barrel", {}, kFrame).main();
    const Camera lift = buildEffect("inverse-perspective", {{"gain", {0.3}}}, kFrame).main();
    const DocumentArtcam whole = assembleDocumentArtcam(
        Artcam(twist), {{"barrel", {}}, {"inverse-perspective", {{"gain", {0.3}}}}}, kFrame, false);
    QVERIFY2(whole.note.empty(), whole.note.c_str());
    QCOMPARE(whole.applied, (std::vector<int>{0, 1}));
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d(-0.8, 0.5),
                                    Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.6, 0.6)}) {
      const Eigen::Vector2d want = position(lift, position(barrel, position(twist, p)));
      const Eigen::Vector2d got = position(whole.camera.main(), p);
      QVERIFY2((got - want).norm() < 1e-9,
               qPrintable(QString("(%1, %2): off by %3").arg(p.x()).arg(p.y()).arg((got - want).norm())));
    }
  }

  void depthEffectsWaitForDepth() {
    const Artcam base(identityImageCamera(kFrame));
    const std::vector<EffectStep> stack = {{"aerial-perspective", {}}, {"barrel", {}}};
    const DocumentArtcam without = assembleDocumentArtcam(base, stack, kFrame, false);
    QCOMPARE(without.applied, std::vector<int>{1});
    QVERIFY2(without.note.find("effect 1 (Aerial perspective) left out: it reads depth") == 0,
             without.note.c_str());
    QVERIFY(!readsDepth(without.camera));
    const DocumentArtcam with = assembleDocumentArtcam(base, stack, kFrame, true);
    QCOMPARE(with.applied, (std::vector<int>{0, 1}));
    QVERIFY(readsDepth(with.camera));
    QVERIFY(with.note.empty());
  }

  void aerialThenDepthOfFieldIsOneCamera() {
    const Artcam base(identityImageCamera(kFrame));
    const DocumentArtcam ok = assembleDocumentArtcam(
        base, {{"aerial-perspective", {}}, {"depth-of-field", {}}}, kFrame, true);
    QVERIFY2(ok.note.empty(), ok.note.c_str());
    QCOMPARE(ok.camera.depth_output, DepthOutput::BlurVariance);
    // Depth of field must come last (its output is a blur variance, not a depth).
    const DocumentArtcam refused = assembleDocumentArtcam(
        base, {{"depth-of-field", {}}, {"aerial-perspective", {}}}, kFrame, true);
    QCOMPARE(refused.applied, std::vector<int>{0});
    QVERIFY2(refused.note.find("effect 2 (Aerial perspective) left out") == 0,
             refused.note.c_str());
  }

  void largestValidRectIsTheBiggestOpaqueRectangle() {
    // 8×6, opaque except a transparent column at x = 5 and the top-left pixel: the largest
    // opaque rectangle is x 0..4 (5 wide) by y 1..5 (5 tall) = 25 pixels.
    ImageF img(8, 6, 2, 1);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) img.pixel(x, y)[1] = (x == 5 || (x == 0 && y == 0)) ? 0.f : 1.f;
    const ValidRect r = largestValidRect(img);
    QCOMPARE(r.x0, 0);
    QCOMPARE(r.y0, 1);
    QCOMPARE(r.x1, 5);
    QCOMPARE(r.y1, 6);
    ImageF none(3, 3, 2, 1);
    QCOMPARE(largestValidRect(none).width(), 0);
  }

  void exportFillsAndCrops() {
    // A 40×30 grey photo shrunk to half about the centre: the border has no preimage.
    LoadedImage photo;
    photo.image = ImageF(40, 30, 3);
    photo.info.srgb = false;  // linear values, as made here
    for (float& v : photo.image.data) v = 0.25f;
    Camera half = identityImageCamera({40, 30});
    half.stages()[0].q[2](2, 2) = 2.0;  // w' = 2w: every point halves
    ExportOptions fill;
    fill.fill = std::array<float, 4>{1.0f, 0.0f, 0.0f, 1.0f};
    RenderSummary s;
    const ImageF filled = renderExport(photo, nullptr, Artcam(half), fill, {}, &s);
    QCOMPARE(filled.channels, 3);  // opaque everywhere after the fill: alpha dropped
    const float* corner = filled.pixel(1, 1);
    QCOMPARE(corner[0], 1.0f);
    QCOMPARE(corner[1], 0.0f);
    const float* centre = filled.pixel(20, 15);
    QVERIFY(std::abs(centre[0] - 0.25f) < 1e-5f && std::abs(centre[1] - 0.25f) < 1e-5f);
    ExportOptions crop;
    crop.crop_to_valid = true;
    const ImageF cropped = renderExport(photo, nullptr, Artcam(half), crop, {}, &s);
    // The valid part is the middle half: 20×15 (pixel centres inside it), give or take the edge.
    QVERIFY2(std::abs(cropped.width - 20) <= 1 && std::abs(cropped.height - 15) <= 1,
             qPrintable(QString("%1x%2").arg(cropped.width).arg(cropped.height)));
    QCOMPARE(cropped.channels, 3);
  }
};

QTEST_GUILESS_MAIN(TestDocumentCamera)
#include "test_document_camera.moc"
