// SPDX-License-Identifier: Apache-2.0
// The effects panel's renderer: the newest-request worker (newest_request_slot.h, after Qt's
// Mandelbrot example, like RenderWorker). One thread; a request made while one renders
// replaces the pending one and cancels the running pass between bands (its progress hook sees
// keepGoing() turn false), so the GUI thread never waits for a render. Results come back by a
// queued signal with the request's generation stamp; no exception leaves run() (it becomes the
// result's message).
//
// The thumbnail (the photo's preview copy box-downscaled to kThumbnailSide) and the stand-in
// depth ramp are made here, on the worker, not on the GUI thread.
#pragma once

#include "core/effects/effect_table.h"
#include "ui/newest_request_slot.h"
#include "ui/photo.h"

#include <QImage>
#include <QString>
#include <QThread>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace artcam::ui {

struct EffectRequest {
  PhotoPtr photo;                       // its preview copy is the source
  std::shared_ptr<const ImageF> depth;  // null: the stand-in ramp
  std::string effect;
  EffectValues values;
  quint64 generation = 0;
};

struct EffectResult {
  QImage image;     // null when the render failed
  QString message;  // the path and time, or why it failed
};

class EffectsRenderWorker : public QThread {
  Q_OBJECT

 public:
  static constexpr int kThumbnailSide = 384;
  // One render of a request; `keep_going` polled between bands (false: cancelled, then the
  // result is empty). The one place that calls the renderer.
  using Render =
      std::function<EffectResult(const EffectRequest&, const std::function<bool()>& keep_going)>;
  static EffectResult renderEffectPreview(const EffectRequest& request,
                                          const std::function<bool()>& keep_going);
  // Far at the top, near at the bottom, log-spaced from 1 to 100: a ground plane seen level.
  static ImageF standInDepth(int width, int height);

  explicit EffectsRenderWorker(QObject* parent = nullptr);
  ~EffectsRenderWorker() override;  // cancels the render in flight and joins (at shutdown)

  // GUI thread, before the first request: replaces the render (tests make it slow).
  void setRender(Render render) { render_ = std::move(render); }
  // GUI thread. Replaces the pending request; cancels the one in flight at its next band.
  void request(EffectRequest request);

 signals:
  void rendered(quint64 generation, const QImage& image, const QString& message);

 protected:
  void run() override;

 private:
  Render render_ = &EffectsRenderWorker::renderEffectPreview;
  NewestRequestSlot<EffectRequest> slot_;
};

}  // namespace artcam::ui
