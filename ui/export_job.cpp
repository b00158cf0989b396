#include "ui/export_job.h"

#include "core/io/image_io.h"
#include "core/render/attributed.h"
#include "core/render/warp.h"
#include "ui/render_worker.h"

#include <exception>
#include <string>

namespace artcam::ui {

ExportJob::ExportJob(PhotoPtr photo, Camera camera, QString path, QObject* parent)
    : QThread(parent),
      photo_(std::move(photo)),
      camera_(std::move(camera)),
      path_(std::move(path)) {}

ExportJob::~ExportJob() {
  cancel_ = true;
  wait();
}

void ExportJob::run() {
  try {
    WarpOptions options;
    options.filter = Filter::Bicubic;
    int last = -1;
    options.progress = [this, &last](double f) {
      const int percent = static_cast<int>(f * 95.0);  // the rest is writing
      if (percent != last) {
        last = percent;
        emit progressChanged(percent);
      }
      return !cancel_.load();
    };
    WarpSummary summary;
    ImageF out;
    if (RenderWorker::needsAttributes(camera_)) {
      AttributedOptions a;
      a.filter = options.filter;
      a.progress = options.progress;
      AttributedSummary as;
      out = renderAttributed(photo_->full.image, depth_.get(), camera_, a, &as).colour;
      summary.cancelled = as.cancelled;
      summary.kernel = std::string(attributedPathName(as.path)) + (as.kernel.empty() ? "" : " " + as.kernel);
      summary.render_ms = as.render_ms;
    } else {
      out = warpImage(photo_->full.image, camera_, options, &summary);
    }
    if (summary.cancelled || cancel_) {
      emit done(false, tr("Export cancelled."));
      return;
    }
    const Status status = writeImage(path_.toStdString(), out, &photo_->full.info);
    if (!status) {
      emit done(false, QString::fromStdString(status.message));
      return;
    }
    emit progressChanged(100);
    emit done(true, tr("Exported %1 (%2 kernel, %3 ms)")
                        .arg(path_, QString::fromStdString(summary.kernel))
                        .arg(summary.render_ms, 0, 'f', 0));
  } catch (const std::exception& e) {
    emit done(false, tr("Export of %1 failed: %2").arg(path_, QString::fromUtf8(e.what())));
  } catch (...) {
    emit done(false, tr("Export of %1 failed: unknown error").arg(path_));
  }
}

}  // namespace artcam::ui
