// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/effects_render_worker.h"

#include "core/pipeline/render.h"
#include "ui/image_convert.h"

#include <cmath>
#include <exception>

namespace artcam::ui {

ImageF EffectsRenderWorker::standInDepth(int w, int h) {
  ImageF depth(w, h, 1);
  for (int y = 0; y < h; ++y) {
    const float d = static_cast<float>(std::pow(100.0, 1.0 - (y + 0.5) / h));
    for (int x = 0; x < w; ++x) depth.pixel(x, y)[0] = d;
  }
  return depth;
}

EffectResult EffectsRenderWorker::renderEffectPreview(const EffectRequest& request,
                                                      const std::function<bool()>& keep_going) {
  const ImageF source = boxDownscale(request.photo->preview, kThumbnailSide);
  const FrameSize frame{source.width, source.height};
  const bool stand_in = !request.depth || request.depth->empty();
  // Any size: the renderer reads the depth at the same place (attributed.h).
  const ImageF depth = stand_in ? standInDepth(frame.width, frame.height) : *request.depth;
  const Artcam camera = buildEffect(request.effect, request.values, frame);
  RenderOptions options;
  options.warp.progress = [&keep_going](double) { return keep_going(); };
  RenderSummary summary;
  const ImageF out = render(RenderInputs::of(source, &depth), camera, options, &summary);
  if (summary.cancelled) return {};
  EffectResult result;
  result.image = qimageFromLinear(out);
  result.message = QString("%1, %2 ms")
                       .arg(QString::fromStdString(summary.describe()))
                       .arg(summary.render_ms, 0, 'f', 1);
  const EffectSpec* spec = findEffect(request.effect);
  if (spec && spec->needs_depth && stand_in)
    result.message += "; " + tr("no depth painted: a ramp stands in (far at the top)");
  return result;
}

EffectsRenderWorker::EffectsRenderWorker(QObject* parent) : QThread(parent) {}

EffectsRenderWorker::~EffectsRenderWorker() { slot_.shutdown(*this); }

void EffectsRenderWorker::request(EffectRequest request) { slot_.put(std::move(request), *this); }

void EffectsRenderWorker::run() {
  for (;;) {
    std::optional<EffectRequest> next = slot_.take();
    if (!next) return;
    const quint64 generation = next->generation;
    EffectResult result;
    try {
      if (!next->photo || next->photo->preview.empty()) continue;
      result = render_(*next, [this] { return slot_.keepGoing(); });
    } catch (const std::exception& e) {
      result = {QImage(), tr("cannot render: %1").arg(QString::fromUtf8(e.what()))};
    } catch (...) {
      result = {QImage(), tr("cannot render: unknown error")};
    }
    if (!slot_.keepGoing()) continue;  // a newer request arrived: drop this one
    emit rendered(generation, result.image, result.message);
  }
}

}  // namespace artcam::ui
