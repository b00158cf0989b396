// SPDX-License-Identifier: Apache-2.0
#include "ui/image_loader.h"

namespace artcam::ui {

namespace {

struct LoadOutcome {
  PhotoPtr photo;  // null: `message` says why, or the load was cancelled
  QString message;
};

}  // namespace

ImageLoader::ImageLoader(QString path, QObject* parent) : QObject(parent), path_(std::move(path)) {
  qRegisterMetaType<PhotoPtr>();
}

ImageLoader::~ImageLoader() { cancel(); }

void ImageLoader::cancel() {
  if (job_) job_->cancel();
}

void ImageLoader::start() {
  if (job_) return;
  job_ = runInBackground(
      this,
      [path = path_](JobContext& job) {
        ReadImageOptions options;
        // The last 10 % are the reduced copies.
        options.progress = [&job](double f) { return job.progress(f * 0.9); };
        Result<LoadedImage> result = readImage(path.toStdString(), options);
        if (job.cancelled()) return LoadOutcome{};
        if (!result) return LoadOutcome{nullptr, QString::fromStdString(result.status.message)};
        PhotoPtr photo = makePhoto(path, std::move(*result.value));
        if (job.cancelled()) return LoadOutcome{};
        job.setProgress(1.0);
        return LoadOutcome{std::move(photo), QString()};
      },
      [this](JobOutcome<LoadOutcome> outcome) {
        if (!outcome.cancelled) {
          if (!outcome.value)
            emit failed(tr("Could not load %1: %2").arg(path_, outcome.error));
          else if (outcome.value->photo)
            emit loaded(outcome.value->photo);
          else
            emit failed(outcome.value->message);
        }
        emit finished();
      });
  connect(job_, &BackgroundJob::progressChanged, this, &ImageLoader::progressChanged);
}

}  // namespace artcam::ui
