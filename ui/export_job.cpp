// SPDX-License-Identifier: Apache-2.0
#include "ui/export_job.h"

#include "core/io/image_io.h"

#include <string>

namespace artcam::ui {

namespace {

struct ExportOutcome {
  bool ok = false;
  QString message;
};

}  // namespace

QString ExportJob::writtenText(const QString& path, const ImageF& out,
                               const RenderSummary& summary) {
  // What is in the file: its size, whether it kept an alpha channel, how many of its pixels are
  // transparent (none after a fill or a crop), and what the export did to get there.
  QString text = tr("Wrote %1: %2×%3").arg(path).arg(out.width).arg(out.height);
  text += out.alpha_channel >= 0 ? tr(" with alpha") : tr(", opaque");
  if (summary.transparent_pixels > 0)
    text += tr(", %1 transparent pixels").arg(summary.transparent_pixels);
  if (!summary.note.empty()) text += "; " + QString::fromStdString(summary.note);
  return text +
         tr(" (%1, %2 ms)")
             .arg(QString::fromUtf8(renderPathName(summary.path).data(),
                                    static_cast<qsizetype>(renderPathName(summary.path).size())))
             .arg(summary.render_ms, 0, 'f', 0);
}

ExportJob::ExportJob(PhotoPtr photo, Artcam camera, QString path, ExportOptions options,
                     QObject* parent)
    : QObject(parent),
      photo_(std::move(photo)),
      camera_(std::move(camera)),
      options_(std::move(options)),
      path_(std::move(path)) {}

ExportJob::~ExportJob() { cancel(); }

void ExportJob::cancel() {
  if (job_) job_->cancel();
}

ImageF ExportJob::render(const LoadedImage& photo, const ImageF* depth, const Artcam& camera,
                         const ExportOptions& options, const std::function<bool(double)>& progress,
                         RenderSummary* summary, const ImageF* second) {
  return renderExport(photo, depth, camera, options, progress, summary, second);
}

void ExportJob::start() {
  if (job_) return;
  // A first look has no full pixels (photo.h); its caller waits for the full photo
  // (Document::whenFullImage). Rendering the reduced one would be a silently smaller export.
  if (!photo_->hasFullImage()) {
    QMetaObject::invokeMethod(this, [this] {
      emit done(false, tr("Export of %1: the full photo is not decoded yet.").arg(path_));
      emit finished();
    }, Qt::QueuedConnection);
    return;
  }
  // Everything the work reads is copied or shared here: the job never touches this object.
  job_ = runInBackground(
      this,
      [photo = photo_, camera = camera_, path = path_, depth = depth_, second = second_,
       options = options_](JobContext& job) {
        RenderSummary summary;
        const ImageF out = render(
            photo->full, depth.get(), camera, options,
            [&job](double f) { return job.progress(f * 0.95); },  // the rest is writing
            &summary, second.get());
        if (summary.cancelled || job.cancelled())
          return ExportOutcome{false, tr("Export cancelled.")};
        const Status status =
            writeImage(path.toStdString(), out, &photo->full.info, options.write);
        if (!status) return ExportOutcome{false, QString::fromStdString(status.message)};
        job.setProgress(1.0);
        return ExportOutcome{true, writtenText(path, out, summary)};
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
