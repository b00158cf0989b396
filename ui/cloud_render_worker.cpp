// SPDX-License-Identifier: Apache-2.0
#include "ui/cloud_render_worker.h"

#include "core/render/warp.h"
#include "ui/image_convert.h"

#include <QElapsedTimer>

#include <algorithm>

namespace artcam::ui {

std::optional<ImageF> CloudRenderWorker::renderPass(const CloudRenderRequest& request, int width,
                                                    int height,
                                                    const std::function<bool()>& keep_going) {
  // Leave the GUI one core, as the image preview does.
  const int threads = std::max(1, QThread::idealThreadCount() - 1);
  CloudRenderOptions options;
  options.width = width;
  options.height = height;
  options.point_spacing = request.point_spacing;
  options.layers = request.layers;
  options.threads = threads;
  options.progress = [&](double) { return keep_going(); };
  CloudRenderSummary summary;
  ImageF out = renderCloud(*request.cloud, request.effects, request.view, options, &summary);
  if (summary.cancelled || !keep_going()) return std::nullopt;
  if (request.lens) {
    WarpOptions warp;
    warp.width = width;
    warp.height = height;
    warp.threads = threads;
    warp.progress = [&](double) { return keep_going(); };
    WarpSummary warp_summary;
    out = warpImage(out, *request.lens, warp, &warp_summary);
    if (warp_summary.cancelled || !keep_going()) return std::nullopt;
  }
  return out;
}

CloudRenderWorker::CloudRenderWorker(QObject* parent)
    : NewestRequestWorker(QStringLiteral("the 3D view renderer"), parent) {}

CloudRenderWorker::~CloudRenderWorker() { shutdown(); }

void CloudRenderWorker::serve(CloudRenderRequest& job) {
  if (!job.cloud || job.width <= 0 || job.height <= 0) return;
  const bool coarse_worth_it = std::min(job.width, job.height) >= 8 * kCoarseFactor;
  for (int pass = coarse_worth_it ? 0 : 1; pass < 2 && keepGoing(); ++pass) {
    const bool final_pass = pass == 1;
    const int w = final_pass ? job.width : std::max(1, job.width / kCoarseFactor);
    const int h = final_pass ? job.height : std::max(1, job.height / kCoarseFactor);
    QElapsedTimer timer;
    timer.start();
    const std::optional<ImageF> out = renderPass(job, w, h, [this] { return keepGoing(); });
    if (!out) return;
    const QImage image = qimageFromLinear(*out);
    if (!keepGoing()) return;  // a newer request arrived while converting: drop this one
    emit rendered(image, job.generation, final_pass,
                  static_cast<double>(timer.nsecsElapsed()) / 1e6);
  }
}

}  // namespace artcam::ui
