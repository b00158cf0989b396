// SPDX-License-Identifier: Apache-2.0
#include "ui/render_worker.h"

#include "core/effects/finish.h"
#include "core/pipeline/camera_frame.h"
#include "core/pipeline/render.h"
#include "ui/image_convert.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace artcam::ui {

WarpOptions RenderWorker::passOptions(int width, int height) {
  WarpOptions options;
  options.width = width;
  options.height = height;
  // Every core: a pass takes a few tens of milliseconds at most, the GUI thread is idle while
  // the user waits for it, and a newer edit cancels it between tiles anyway. (Leaving one core
  // to the GUI doubled the latency on 2-core machines: 33 → 16 ms per 1920-wide pass.)
  options.threads = std::max(1, QThread::idealThreadCount());
  return options;
}

// Every pass goes through core's render front door: a geometry camera with a pyramid renders
// straight into the RGBA8 QImage; everything else (colour, depth, layers) renders from the float
// preview copy and is encoded for display.
QImage RenderWorker::renderPass(const RenderRequest& job, const WarpOptions& options,
                                WarpSummary* summary,
                                const std::function<bool(const QImage&, double)>& before_marks) {
  const Artcam& camera = job.camera;
  // The pyramid holds the upright photo; a camera applied before the turn renders from the
  // float preview copy, turned back (camera_frame.h).
  const ImageF* source = job.source && !job.source->empty() ? job.source.get() : nullptr;
  const FrameSize upright =
      source        ? FrameSize{source->width, source->height}
      : job.pyramid ? FrameSize{job.pyramid->level(0).width, job.pyramid->level(0).height}
                    : FrameSize{};
  const int turn = turnAfterCamera(camera, upright, job.stored_orientation);
  const bool use_pyramid = job.pyramid && (turn == 1 || !source);
  RenderInputs inputs;
  if (use_pyramid) {
    inputs.photo = job.pyramid->level(0);
    inputs.pyramid = job.pyramid.get();
  }
  if (job.source && !job.source->empty()) {
    inputs.linear = job.source.get();
    if (inputs.photo.empty()) inputs.photo = viewOf(*job.source);
  }
  inputs.depth = job.depth.get();
  inputs.second = job.second.get();
  inputs.encoding = job.encoding.get();
  RenderOptions render_options;
  render_options.warp = options;
  RenderSummary rs;
  QImage image;
  if (use_pyramid && !needsLinearPhoto(camera) && job.finish.empty()) {
    image = QImage(options.width, options.height, QImage::Format_RGBA8888_Premultiplied);
    ImageView view = packedView<void>(image.bits(), image.width(), image.height(), 4,
                                      PixelType::UInt8, /*alpha_channel=*/3);
    view.row_bytes = image.bytesPerLine();
    renderTurned(inputs, camera, render_options, turn, view, &rs);
  } else {
    ImageF out = renderTurned(inputs, camera, render_options, turn, &rs);
    if (!rs.cancelled && !job.finish.empty() && before_marks &&
        !before_marks(qimageFromLinear(out), rs.render_ms))
      rs.cancelled = true;
    if (!rs.cancelled && !job.finish.empty()) {
      const StoredEncoding linear;
      if (const Status marked =
              applyFinishLinear(out, job.encoding ? *job.encoding : linear, job.finish);
          !marked)
        throw std::runtime_error(marked.message);
    }
    if (!rs.cancelled) image = qimageFromLinear(out);
  }
  if (summary) {
    summary->cancelled = rs.cancelled;
    summary->kernel = rs.kernel;
    summary->transparent_pixels = rs.transparent_pixels;
    summary->render_ms = rs.render_ms;
    summary->note = rs.note;
  }
  if (rs.cancelled) return {};
  return image;
}

RenderWorker::RenderWorker(QObject* parent)
    : NewestRequestWorker(QStringLiteral("the preview renderer"), parent) {}

RenderWorker::~RenderWorker() { shutdown(); }

void RenderWorker::serve(RenderRequest& job) {
  const bool has_source = job.pyramid || (job.source && !job.source->empty());
  if (!has_source || job.width <= 0 || job.height <= 0) return;
  const bool coarse_worth_it =
      std::min(job.width, job.height) >= 8 * kCoarseFactor && last_final_ms_ > kCoarseAboveMs;
  for (int pass = coarse_worth_it ? 0 : 1; pass < 2 && keepGoing(); ++pass) {
    const bool final_pass = pass == 1;
    WarpOptions options = final_pass ? passOptions(job.width, job.height)
                                     : passOptions(std::max(1, job.width / kCoarseFactor),
                                                   std::max(1, job.height / kCoarseFactor));
    options.progress = [this](double) { return keepGoing(); };
    WarpSummary summary;
    // The marks take G'MIC a good part of a second and cannot be cancelled: the final pass
    // shows the picture without them first (a drag stays live), then the marked one when no
    // newer edit came.
    const auto plain_first = [&](const QImage& plain, double render_ms) {
      if (!keepGoing()) return false;
      emit rendered(plain, job.generation, /*final_pass=*/false, render_ms);
      return true;
    };
    const QImage image =
        renderPass(job, options, &summary,
                   final_pass ? std::function<bool(const QImage&, double)>(plain_first)
                              : std::function<bool(const QImage&, double)>());
    if (summary.cancelled || !keepGoing()) return;  // a newer request arrived: drop this one
    if (final_pass) last_final_ms_ = summary.render_ms;
    emit rendered(image, job.generation, final_pass, summary.render_ms);
  }
}

}  // namespace artcam::ui
