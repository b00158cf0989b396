// SPDX-License-Identifier: Apache-2.0
// The 3D view's renderer, a newest-request worker like RenderWorker (newest_request_worker.h,
// after Qt's Mandelbrot example): one pending request slot where the newest wins, std::atomic
// restart/abort flags polled between row bands through the renderers' progress hooks, a coarse
// pass (1/4 size) before the full one, results by queued signal with the request's generation
// stamp; a pass that throws is a `failed` signal and the next request is served.
//
// A pass: the cloud through the 3D effect (object space) and the orbit's pinhole
// (core/cloud/cloud_render.h), then, when the document has a non-identity image camera, that
// camera applied to the rendered view as a lens in front of it (gather warp, as the preview).
#pragma once

#include "core/cloud/cloud_render.h"
#include "core/cloud/point_cloud.h"
#include "core/model/camera.h"
#include "ui/newest_request_worker.h"

#include <QImage>
#include <QString>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

struct CloudRenderRequest {
  std::shared_ptr<const PointCloud> cloud;
  std::vector<Camera> effects;  // 3D cameras before the view (may be empty)
  Camera view;                  // the projecting camera (orbit pinhole)
  std::optional<Camera> lens;   // the document's image camera, applied to the rendered view
  RenderLayers layers = RenderLayers::Whole;
  double point_spacing = 0.0;
  int width = 0;  // full-pass size
  int height = 0;
  quint64 generation = 0;
};

class CloudRenderWorker : public NewestRequestWorker<CloudRenderRequest> {
  Q_OBJECT

 public:
  static constexpr int kCoarseFactor = 4;

  // One pass at width×height: what run() does per pass, so a direct call reproduces the
  // worker's image. `keep_going` returning false cancels (then the result is empty).
  static std::optional<ImageF> renderPass(const CloudRenderRequest& request, int width,
                                          int height, const std::function<bool()>& keep_going);

  // request() (GUI thread) and shutdown() (idempotent) are NewestRequestWorker's.
  explicit CloudRenderWorker(QObject* parent = nullptr);
  ~CloudRenderWorker() override;  // aborts any render and joins the thread

 signals:
  void rendered(const QImage& image, quint64 generation, bool final_pass, double render_ms);

 protected:
  void serve(CloudRenderRequest& job) override;
};

}  // namespace artcam::ui
