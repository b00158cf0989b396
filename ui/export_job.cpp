#include "ui/export_job.h"

#include "core/io/image_io.h"
#include "core/render/attributed.h"
#include "ui/render_worker.h"

#include <string>

namespace artcam::ui {

namespace {

struct ExportOutcome {
  bool ok = false;
  QString message;
};

}  // namespace

ExportJob::ExportJob(PhotoPtr photo, Camera camera, QString path, QObject* parent)
    : QObject(parent),
      photo_(std::move(photo)),
      camera_(std::move(camera)),
      path_(std::move(path)) {}

ExportJob::~ExportJob() { cancel(); }

void ExportJob::cancel() {
  if (job_) job_->cancel();
}

ImageF ExportJob::render(const ImageF& photo, const ImageF* depth, const Camera& camera,
                         const std::function<bool(double)>& progress, WarpSummary* summary) {
  if (RenderWorker::needsAttributes(camera)) {
    AttributedOptions a;
    a.filter = Filter::Bicubic;
    a.progress = progress;
    AttributedSummary as;
    ImageF out = renderAttributed(photo, depth, camera, a, &as).colour;
    summary->cancelled = as.cancelled;
    summary->kernel =
        std::string(attributedPathName(as.path)) + (as.kernel.empty() ? "" : " " + as.kernel);
    summary->render_ms = as.render_ms;
    return out;
  }
  WarpOptions options;
  options.filter = Filter::Bicubic;
  options.progress = progress;
  return warpImage(photo, camera, options, summary);
}

void ExportJob::start() {
  if (job_) return;
  // Everything the work reads is copied or shared here: the job never touches this object.
  job_ = runInBackground(
      this,
      [photo = photo_, camera = camera_, path = path_, depth = depth_](JobContext& job) {
        WarpSummary summary;
        const ImageF out = render(
            photo->full.image, depth.get(), camera,
            [&job](double f) { return job.progress(f * 0.95); },  // the rest is writing
            &summary);
        if (summary.cancelled || job.cancelled())
          return ExportOutcome{false, tr("Export cancelled.")};
        const Status status = writeImage(path.toStdString(), out, &photo->full.info);
        if (!status) return ExportOutcome{false, QString::fromStdString(status.message)};
        job.setProgress(1.0);
        return ExportOutcome{true, tr("Exported %1 (%2 kernel, %3 ms)")
                                       .arg(path, QString::fromStdString(summary.kernel))
                                       .arg(summary.render_ms, 0, 'f', 0)};
      },
      [this](JobOutcome<ExportOutcome> outcome) {
        if (outcome.value)
          emit done(outcome.value->ok, outcome.value->message);
        else
          emit done(false, tr("Export of %1 failed: %2").arg(path_, outcome.error));
        emit finished();
      });
  connect(job_, &BackgroundJob::progressChanged, this, &ExportJob::progressChanged);
}

}  // namespace artcam::ui
