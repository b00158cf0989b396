#include "ui/render_worker.h"

#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "core/render/warp.h"
#include "ui/image_convert.h"

#include <algorithm>
#include <exception>
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

bool RenderWorker::needsAttributes(const Camera& camera) {
  const CameraStructure s = analyseStructure(camera);
  return s.attributes_change || s.geometry_depends_on_attributes;
}

QImage RenderWorker::renderPass(const RenderRequest& job, const WarpOptions& options,
                                WarpSummary* summary) {
  if (needsAttributes(job.camera)) {
    if (!job.source || job.source->empty())
      throw std::invalid_argument("a camera that changes colour needs the float preview copy");
    AttributedOptions a;
    a.filter = options.filter;
    a.width = options.width;
    a.height = options.height;
    a.threads = options.threads;
    a.progress = options.progress;
    AttributedSummary as;
    const AttributedImage out = renderAttributed(*job.source, job.depth.get(), job.camera, a, &as);
    if (summary) {
      summary->cancelled = as.cancelled;
      summary->kernel = std::string(attributedPathName(as.path)) + (as.kernel.empty() ? "" : " " + as.kernel);
      summary->transparent_pixels = as.transparent_pixels;
      summary->render_ms = as.render_ms;
      summary->note = as.note;
    }
    if (as.cancelled) return {};
    return qimageFromLinear(out.colour);
  }
  if (job.pyramid) {
    QImage out(options.width, options.height, QImage::Format_RGBA8888_Premultiplied);
    ImageView view = packedView<void>(out.bits(), out.width(), out.height(), 4, PixelType::UInt8,
                                      /*alpha_channel=*/3);
    view.row_bytes = out.bytesPerLine();
    warpPreview(*job.pyramid, job.camera, view, options, summary);
    return out;
  }
  return qimageFromLinear(warpImage(*job.source, job.camera, options, summary));
}

RenderWorker::RenderWorker(QObject* parent) : QThread(parent) {}

RenderWorker::~RenderWorker() { shutdown(); }

void RenderWorker::request(RenderRequest request) { slot_.put(std::move(request), *this); }

void RenderWorker::shutdown() { slot_.shutdown(*this); }

void RenderWorker::run() {
  for (;;) {
    std::optional<RenderRequest> next = slot_.take();
    if (!next) return;
    RenderRequest job = std::move(*next);
    try {
      const bool has_source = job.pyramid || (job.source && !job.source->empty());
      if (!has_source || job.width <= 0 || job.height <= 0) continue;
      const bool coarse_worth_it = std::min(job.width, job.height) >= 8 * kCoarseFactor &&
                                   last_final_ms_ > kCoarseAboveMs;
      for (int pass = coarse_worth_it ? 0 : 1; pass < 2 && keepGoing(); ++pass) {
        const bool final_pass = pass == 1;
        WarpOptions options = final_pass ? passOptions(job.width, job.height)
                                         : passOptions(std::max(1, job.width / kCoarseFactor),
                                                       std::max(1, job.height / kCoarseFactor));
        options.progress = [this](double) { return keepGoing(); };
        WarpSummary summary;
        const QImage image = renderPass(job, options, &summary);
        if (summary.cancelled || !keepGoing()) break;  // a newer request arrived: drop this one
        if (final_pass) last_final_ms_ = summary.render_ms;
        emit rendered(image, job.generation, final_pass, summary.render_ms);
      }
    } catch (const std::exception& e) {
      emit failed(QString::fromUtf8(e.what()), job.generation);
    } catch (...) {
      emit failed(QStringLiteral("unknown error in the preview renderer"), job.generation);
    }
  }
}

}  // namespace artcam::ui
