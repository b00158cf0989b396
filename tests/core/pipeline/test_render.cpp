// SPDX-License-Identifier: Apache-2.0
// The render front door (core/pipeline/render.h): the output-frame rule, the path chosen for
// each camera kind, agreement with the renderers it dispatches to, alpha only where needed.
#include "core/effects/aerial.h"
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/render.h"
#include "core/render/attributed.h"
#include "core/render/warp.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

ImageF ramp(int w, int h, int channels = 3) {
  ImageF image(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixel(x, y)[c] = static_cast<float>(0.1 + 0.8 * (x + 0.3 * c * y) / (w + h));
  return image;
}

double maxDifference(const ImageF& a, const ImageF& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) return 1e9;
  double worst = 0;
  for (size_t i = 0; i < a.data.size(); ++i) worst = std::max(worst, double(std::abs(a.data[i] - b.data[i])));
  return worst;
}

}  // namespace

class TestRender : public QObject {
  Q_OBJECT

 private slots:
  void outputFrameKeepsThePhotosSize() {
    // A camera made on a 600×400 preview, applied to a 451×300 photo: 451×300, not 451×301.
    const Artcam camera(test::randomHomographyCamera({600, 400}, {600, 400}));
    OutputFrame f = outputFrameFor(camera, {451, 300});
    QCOMPARE(f.size, (FrameSize{451, 300}));
    QVERIFY(f.warning.empty());
    // Target frame twice the source: twice the photo.
    Artcam doubled(test::randomHomographyCamera({600, 400}, {1200, 800}));
    QCOMPARE(outputFrameFor(doubled, {451, 300}).size, (FrameSize{902, 600}));
    // A portrait photo through a landscape camera: stretched, and said so with both sizes.
    f = outputFrameFor(camera, {400, 600});
    QCOMPARE(f.size, (FrameSize{400, 600}));
    QVERIFY(f.warning.find("400x600") != std::string::npos);
    QVERIFY(f.warning.find("600x400") != std::string::npos);
    // An explicit size wins; one side follows the target's aspect.
    QCOMPARE(outputFrameFor(camera, {451, 300}, 300, 0).size, (FrameSize{300, 200}));
  }

  void geometryCamerasRenderAsTheWarpDoes() {
    const FrameSize size{240, 160};
    const Camera lens = test::randomRationalCamera(size, size, 0.05);
    const ImageF photo = ramp(size.width, size.height);
    RenderSummary summary;
    const ImageF front = render(RenderInputs::of(photo), Artcam(lens), {}, &summary);
    const ImageF direct = warpImage(photo, lens);
    QCOMPARE(summary.path, RenderPath::Geometry);
    QCOMPARE(maxDifference(front, direct), 0.0);
    QCOMPARE(summary.size, size);
    QVERIFY(!summary.describe().empty());
  }

  void eachKindTakesItsPath() {
    const FrameSize size{120, 80};
    const ImageF photo = ramp(size.width, size.height);
    ImageF depth(size.width, size.height, 1);
    std::fill(depth.data.begin(), depth.data.end(), 5.0f);

    Artcam layered;
    layered.layers = rgbShiftLayers({}, size, size);
    RenderSummary s;
    ImageF out = render(RenderInputs::of(photo), layered, {}, &s);
    QCOMPARE(s.path, RenderPath::Layered);
    // Channel-split layers take the per-channel gather on the photo as stored (warpChannels),
    // and give the attributed renderer's own layer sum: the same positions and the same rule
    // for alpha (the least coverage), up to the order of float operations.
    QVERIFY2(s.kernel.rfind("per-channel", 0) == 0, s.kernel.c_str());
    QVERIFY(maxDifference(out, renderLayers(photo, nullptr, layered.layers).colour) < 1e-6);

    const Artcam aerial(aerialPerspectiveCamera({}, size, size));
    out = render(RenderInputs::of(photo, &depth), aerial, {}, &s);
    QCOMPARE(s.path, RenderPath::ColourOnly);
    QVERIFY(!s.blurred);

    Artcam dof(depthOfFieldCamera({2.0, 0.05}, size, size));
    dof.depth_output = DepthOutput::BlurVariance;
    ImageF depth_out;
    out = render(RenderInputs::of(photo, &depth), dof, {}, &s, &depth_out);
    QVERIFY(s.blurred);
    QCOMPARE(depth_out.width, size.width);
    // σ² of the thin lens at d = 5, f = 2: (k(d − f)/d)² in the normalised frame's units > 0.
    QVERIFY(depth_out.pixel(60, 40)[0] > 0.0f);

    // A camera that reads depth without a depth image is a broken contract, said in words.
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, render(RenderInputs::of(photo), aerial));
  }

  void piecewiseFollowsTheFrameRule() {
    // Two patches, each the same homography: the mesh warp equals that homography's warp.
    const FrameSize size{200, 100};
    const Camera h = test::randomHomographyCamera(size, size);
    Artcam camera(h);
    PiecewiseCamera pieces;
    pieces.source_size = pieces.target_size = size;
    pieces.patches.push_back({{0, 0, 100, 100}, {}, h, "homography", 0, 0, 0, true});
    pieces.patches.push_back({{100, 0, 200, 100}, {}, h, "homography", 0, 0, 0, true});
    camera.pieces = pieces;
    // A photo at half the camera's resolution renders at half its target frame.
    const ImageF photo = ramp(100, 50);
    RenderSummary s;
    const ImageF out = render(RenderInputs::of(photo), camera, {}, &s);
    QCOMPARE(s.path, RenderPath::Piecewise);
    QCOMPARE(out.width, 100);
    QCOMPARE(out.height, 50);
    WarpOptions half;
    half.width = 100;
    half.height = 50;
    const ImageF gathered = warpImage(photo, h, half);
    // Interior pixels agree to the mesh's linearisation (step 4 px of the full frame).
    double worst = 0;
    for (int y = 10; y < 40; ++y)
      for (int x = 10; x < 90; ++x)
        if (out.pixel(x, y)[3] > 0.999f && gathered.pixel(x, y)[3] > 0.999f)
          worst = std::max(worst, double(std::abs(out.pixel(x, y)[1] - gathered.pixel(x, y)[1])));
    QVERIFY2(worst < 2e-3, qPrintable(QString::number(worst)));
  }

  void alphaOnlyWhereNeeded() {
    ImageF opaque(4, 3, 4, 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        float* p = opaque.pixel(x, y);
        p[0] = 0.1f * x, p[1] = 0.2f * y, p[2] = 0.3f, p[3] = 1.0f;
      }
    ImageF holes = opaque;
    holes.pixel(2, 1)[3] = 0.5f;
    QVERIFY(!dropOpaqueAlpha(holes));
    QCOMPARE(holes.channels, 4);
    QVERIFY(dropOpaqueAlpha(opaque));
    QCOMPARE(opaque.channels, 3);
    QCOMPARE(opaque.alpha_channel, -1);
    // The colour survives the repacking, pixel by pixel.
    QCOMPARE(opaque.pixel(3, 2)[0], 0.3f);
    QCOMPARE(opaque.pixel(3, 2)[1], 0.4f);
    QCOMPARE(opaque.pixel(1, 0)[2], 0.3f);
  }

  void cancelReturnsNothing() {
    const FrameSize size{200, 100};
    const ImageF photo = ramp(size.width, size.height);
    RenderOptions options;
    options.warp.progress = [](double) { return false; };
    RenderSummary s;
    Artcam layered;
    layered.layers = rgbShiftLayers({}, size, size);
    const ImageF out = render(RenderInputs::of(photo), layered, options, &s);
    QVERIFY(s.cancelled);
    QVERIFY(out.empty());
  }
};

QTEST_GUILESS_MAIN(TestRender)
#include "test_render.moc"
