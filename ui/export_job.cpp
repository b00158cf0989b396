#include "ui/export_job.h"

#include "core/io/image_io.h"
#include "core/pipeline/render.h"

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
    RenderOptions render_options;
    render_options.warp = options;
    RenderSummary summary;
    const ImageF out =
        render(RenderInputs::of(photo_->full.image, depth_.get()), Artcam(camera_), render_options, &summary);
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
    emit done(true, tr("Exported %1 (%2, %3 ms)")
                        .arg(path_, QString::fromStdString(summary.describe()))
                        .arg(summary.render_ms, 0, 'f', 0));
  } catch (const std::exception& e) {
    emit done(false, tr("Export of %1 failed: %2").arg(path_, QString::fromUtf8(e.what())));
  } catch (...) {
    emit done(false, tr("Export of %1 failed: unknown error").arg(path_));
  }
}

}  // namespace artcam::ui
