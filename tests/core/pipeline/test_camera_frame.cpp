// SPDX-License-Identifier: Apache-2.0
// The camera's frame (core/pipeline/camera_frame.h): which raster a camera is applied to, and
// that applying it to the upright photo of each EXIF orientation gives the pixels of correcting
// the stored raster, then turning it. The turns of the truth are OpenImageIO's ImageBufAlgo
// operations as EXIF 2.32 tag 274 names them for a viewer (2 mirror, 3 rotate 180, 4 flip,
// 5 mirror then rotate 270 CW, 6 rotate 90 CW, 7 mirror then rotate 90 CW, 8 rotate 270 CW).
#include "core/pipeline/camera_frame.h"
#include "tests/support/test_support.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

ImageF pattern(int w, int h) {
  ImageF image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        image.pixel(x, y)[c] = static_cast<float>(
            0.5 + 0.3 * std::sin(0.7 * x + 1.3 * c) * std::cos(0.45 * y) + 0.004 * (x - 2 * y));
  return image;
}

// The photo as a viewer shows a raster tagged `orientation`.
ImageF shownAs(const ImageF& stored, int orientation) {
  OIIO::ImageBuf in(
      OIIO::ImageSpec(stored.width, stored.height, stored.channels, OIIO::TypeDesc::FLOAT));
  in.set_pixels(in.roi(), OIIO::TypeDesc::FLOAT, stored.data.data());
  namespace A = OIIO::ImageBufAlgo;
  OIIO::ImageBuf out;
  switch (orientation) {
    case 2:
      out = A::flop(in);
      break;
    case 3:
      out = A::rotate180(in);
      break;
    case 4:
      out = A::flip(in);
      break;
    case 5:
      out = A::rotate270(A::flop(in));
      break;
    case 6:
      out = A::rotate90(in);
      break;
    case 7:
      out = A::rotate90(A::flop(in));
      break;
    case 8:
      out = A::rotate270(in);
      break;
    default:
      out.copy(in);
      break;
  }
  ImageF image(out.spec().width, out.spec().height, stored.channels, stored.alpha_channel);
  out.get_pixels(out.roi(), OIIO::TypeDesc::FLOAT, image.data.data());
  return image;
}

double maxDifference(const ImageF& a, const ImageF& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) return 1e9;
  double worst = 0;
  for (size_t i = 0; i < a.data.size(); ++i)
    worst = std::max(worst, double(std::abs(a.data[i] - b.data[i])));
  return worst;
}

}  // namespace

class TestCameraFrame : public QObject {
  Q_OBJECT

 private slots:
  void ruleForEachFrame() {
    Artcam lens(test::randomHomographyCamera({600, 400}, {600, 400}));
    // Unmarked: the stored raster's aspect and not the upright one's means the sensor's, at
    // any scale of the photo.
    QCOMPARE(turnAfterCamera(lens, {400, 600}, 6), 6);
    QCOMPARE(turnAfterCamera(lens, {400, 600}, 8), 8);
    QCOMPARE(turnAfterCamera(lens, {200, 300}, 6), 6);
    // Fitted on the upright photo (its source is the upright size): applied after the turn.
    QCOMPARE(turnAfterCamera(lens, {600, 400}, 6), 1);
    // No quarter turn: one aspect for both frames, upright as an unmarked camera always was.
    QCOMPARE(turnAfterCamera(lens, {600, 400}, 3), 1);
    QCOMPARE(turnAfterCamera(lens, {400, 600}, 1), 1);
    // Marked: the mark decides.
    lens.frame = CameraFrame::Sensor;
    QCOMPARE(turnAfterCamera(lens, {600, 400}, 3), 3);
    QCOMPARE(turnAfterCamera(lens, {400, 600}, 1), 1);  // stored as shown: one frame
    lens.frame = CameraFrame::Upright;
    QCOMPARE(turnAfterCamera(lens, {400, 600}, 6), 1);
    // A square source fits both frames: upright.
    const Artcam square(test::randomHomographyCamera({400, 400}, {400, 400}));
    QCOMPARE(turnAfterCamera(square, {400, 400}, 6), 1);
  }

  void everyOrientationCorrectsTheStoredRaster() {
    const ImageF stored = pattern(40, 24);
    Artcam camera(test::randomHomographyCamera({40, 24}, {40, 24}));
    camera.frame = CameraFrame::Sensor;
    RenderOptions options;
    options.warp.threads = 1;
    const ImageF corrected = render(RenderInputs::of(stored), camera, options);
    for (int o = 1; o <= 8; ++o) {
      const ImageF upright = shownAs(stored, o);
      const int turn = turnAfterCamera(camera, {upright.width, upright.height}, o);
      QCOMPARE(turn, o);
      const OutputFrame frame = outputFrameTurned(camera, {upright.width, upright.height}, turn);
      QCOMPARE(frame.size, (FrameSize{upright.width, upright.height}));
      QVERIFY(frame.warning.empty());
      const ImageF got = renderTurned(RenderInputs::of(upright), camera, options, turn);
      const ImageF want = shownAs(corrected, o);
      QVERIFY2(maxDifference(got, want) <= 1e-6,
               qPrintable(QString("orientation %1: %2").arg(o).arg(maxDifference(got, want))));
      // The same into a caller's buffer (the stored-type path of warp and batch).
      ImageF into(frame.size.width, frame.size.height, got.channels, got.alpha_channel);
      renderTurned(RenderInputs::of(upright), camera, options, turn, viewOf(into));
      QVERIFY2(maxDifference(into, want) <= 1e-6, qPrintable(QString("orientation %1").arg(o)));
    }
  }

  // An explicit output size is the upright output's.
  void explicitSizeIsUpright() {
    Artcam camera(test::randomHomographyCamera({600, 400}, {600, 400}));
    camera.frame = CameraFrame::Sensor;
    QCOMPARE(outputFrameTurned(camera, {400, 600}, 6, 200, 300).size, (FrameSize{200, 300}));
    QCOMPARE(outputFrameTurned(camera, {400, 600}, 6, 200, 0).size, (FrameSize{200, 300}));
  }
};

QTEST_GUILESS_MAIN(TestCameraFrame)
#include "test_camera_frame.moc"
