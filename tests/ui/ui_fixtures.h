// SPDX-License-Identifier: Apache-2.0
// Fixtures for the UI tests, made in code: a synthetic photo, pair sets, event helpers.
#pragma once

#include "core/render/preview.h"
#include "core/render/warp.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/image_convert.h"
#include "ui/photo.h"
#include "ui/preview_controller.h"
#include "ui/render_worker.h"

#include <QElapsedTimer>
#include <QMouseEvent>
#include <QPointF>
#include <QtTest/QtTest>

#include <cmath>
#include <vector>

namespace artcam::ui::test {

// A w×h RGB photo with gradients and a grid, so any warp visibly changes it.
inline PhotoPtr syntheticPhoto(int w = 320, int h = 240) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const bool line = (x % 32) < 2 || (y % 32) < 2;
      p[0] = line ? 1.0f : static_cast<float>(x) / w;
      p[1] = line ? 1.0f : static_cast<float>(y) / h;
      p[2] = line ? 1.0f : 0.5f * static_cast<float>((x / 16 + y / 16) % 2);
    }
  LoadedImage loaded;
  loaded.image = std::move(img);
  loaded.info.path = "synthetic.png";
  return makePhoto(QStringLiteral("synthetic.png"), std::move(loaded));
}

// Nine well-spread source points (not on one conic) and targets under a mild non-linear map.
inline std::vector<Pair> ninePairs(int w = 320, int h = 240) {
  const double fx[9] = {0.12, 0.5, 0.86, 0.18, 0.47, 0.81, 0.1, 0.55, 0.9};
  const double fy[9] = {0.15, 0.1, 0.2, 0.52, 0.45, 0.55, 0.85, 0.9, 0.8};
  std::vector<Pair> out;
  for (int i = 0; i < 9; ++i) {
    Pair p;
    p.source = {fx[i] * w, fy[i] * h};
    const double u = fx[i] - 0.5, v = fy[i] - 0.5;
    p.target = {(0.5 + u * (1.0 + 0.15 * (u * u + v * v)) + 0.02) * w,
                (0.5 + v * (1.0 + 0.15 * (u * u + v * v)) - 0.01) * h};
    out.push_back(p);
  }
  return out;
}

inline QPoint widgetPoint(const Canvas& canvas, const Eigen::Vector2d& image) {
  return canvas.view().widgetFromImage(QPointF(image.x(), image.y())).toPoint();
}

// QTest::mouseMove does not carry pressed buttons reliably across Qt versions; send directly.
inline void sendMouse(QWidget* w, QEvent::Type type, const QPoint& pos, Qt::MouseButton button,
                      Qt::MouseButtons buttons, Qt::KeyboardModifiers mods = Qt::NoModifier) {
  QMouseEvent event(type, QPointF(pos), w->mapToGlobal(QPointF(pos)), button, buttons, mods);
  QCoreApplication::sendEvent(w, &event);
}

inline void drag(QWidget* w, const QPoint& from, const QPoint& to, int steps = 8) {
  sendMouse(w, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
  for (int s = 1; s <= steps; ++s) {
    const QPoint p = from + (to - from) * s / steps;
    sendMouse(w, QEvent::MouseMove, p, Qt::NoButton, Qt::LeftButton);
  }
  sendMouse(w, QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
}

// Waits until the controller shows the final pass of its newest request.
inline bool waitForNewestPreview(const PreviewController& c, int timeout_ms = 60000) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < timeout_ms) {
    if (c.imageIsFinal() && c.imageGeneration() == c.requestedGeneration() && !c.image().isNull())
      return true;
    QTest::qWait(5);
  }
  return false;
}

// The preview a direct render of the document's current camera gives: core's warpPreview from
// the photo's 8-bit pyramid at the live preview size, with the worker's options.
inline QImage directPreviewRender(const Document& d) {
  const PhotoPtr& photo = d.photo();
  const FrameSize size = livePreviewSize(*photo);
  QImage out(size.width, size.height, QImage::Format_RGBA8888_Premultiplied);
  ImageView view = packedView<void>(out.bits(), size.width, size.height, 4, PixelType::UInt8, 3);
  view.row_bytes = out.bytesPerLine();
  warpPreview(*photo->pyramid, d.camera(), view, RenderWorker::passOptions(size.width, size.height));
  return out;
}

// Mean absolute difference per 8-bit colour channel (alpha ignored) of two images of one size.
inline double meanDifference(const QImage& a, const QImage& b) {
  const QImage x = a.convertToFormat(QImage::Format_RGBA8888);
  const QImage y = b.convertToFormat(QImage::Format_RGBA8888);
  double sum = 0.0;
  for (int r = 0; r < x.height(); ++r) {
    const uchar* p = x.constScanLine(r);
    const uchar* q = y.constScanLine(r);
    for (int c = 0; c < x.width() * 4; ++c)
      if (c % 4 != 3) sum += std::abs(int(p[c]) - int(q[c]));
  }
  return sum / (3.0 * x.width() * x.height());
}

inline void click(QWidget* w, const QPoint& pos, Qt::KeyboardModifiers mods = Qt::NoModifier) {
  sendMouse(w, QEvent::MouseButtonPress, pos, Qt::LeftButton, Qt::LeftButton, mods);
  sendMouse(w, QEvent::MouseButtonRelease, pos, Qt::LeftButton, Qt::NoButton, mods);
}

}  // namespace artcam::ui::test
