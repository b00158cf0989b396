// SPDX-License-Identifier: Apache-2.0
#include "ui/image_loader.h"

#include "core/io/stored_image.h"
#include "core/util/memory_budget.h"

#include <QTimer>

#include <algorithm>
#include <string>

namespace artcam::ui {

namespace {

struct LoadOutcome {
  PhotoPtr photo;  // null: `message` says why, or the load was cancelled
  QString message;
};

// What the studio holds per photo pixel beside the photo as float (4 bytes a channel, at least
// the 4 of a render): the depth raster the planes make at its size (8) and the full-size float
// RGBA render an export makes (16). The reduced copies are bounded (photo.h) and left out.
constexpr double kStudioBytesPerPixelBesideThePhoto = 8.0 + 16.0;

// "" when a photo of this header fits the memory budget as the studio holds it, else why not.
// Checked from the header before any pixel is decoded: the readers' own check counts the
// float photo alone, which is what the command line holds.
QString studioMemoryProblem(const QString& path) {
  const Result<StoredShape> shape = readStoredShape(path.toStdString());
  if (!shape) return {};  // the read that follows names what is wrong with the file
  const double pixels = static_cast<double>(shape->width) * static_cast<double>(shape->height);
  const double bytes =
      pixels * (4.0 * std::max(4, shape->channels) + kStudioBytesPerPixelBesideThePhoto);
  if (bytes <= memoryBudgetBytes()) return {};
  return QString::fromStdString(
      path.toStdString() + ": cannot open: " + std::to_string(shape->width) + "x" +
      std::to_string(shape->height) + " pixels need " + describeBytes(bytes) +
      " in the studio (the photo, its depth and its full-size render), "
      "more than " +
      describeMemoryBudget());
}

// readImage and the reduced copies, progress 0…1 over both.
LoadOutcome readPhoto(const QString& path, JobContext& job) {
  if (const QString problem = studioMemoryProblem(path); !problem.isEmpty())
    return LoadOutcome{nullptr, problem};
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
}

// The first look (core/io/first_look.h) when the file has one, else the whole read.
LoadOutcome readFirstLookOrPhoto(const QString& path, JobContext& job) {
  if (const QString problem = studioMemoryProblem(path); !problem.isEmpty())
    return LoadOutcome{nullptr, problem};
  Result<std::optional<FirstLook>> look =
      readFirstLook(path.toStdString(), kLivePreviewMaxWidth, kLivePreviewMaxHeight,
                    [&job](double f) { return job.progress(f * 0.9); });
  if (job.cancelled()) return LoadOutcome{};
  if (!look) return LoadOutcome{nullptr, QString::fromStdString(look.status.message)};
  if (!*look.value) return readPhoto(path, job);
  PhotoPtr photo = makeFirstLookPhoto(path, std::move(**look.value));
  if (job.cancelled()) return LoadOutcome{};
  job.setProgress(1.0);
  return LoadOutcome{std::move(photo), QString()};
}

}  // namespace

ImageLoader::ImageLoader(QString path, QObject* parent) : QObject(parent), path_(std::move(path)) {
  qRegisterMetaType<PhotoPtr>();
}

ImageLoader::~ImageLoader() { cancel(); }

void ImageLoader::cancel() {
  cancelled_ = true;
  if (job_) job_->cancel();
}

void ImageLoader::start() {
  if (job_) return;
  job_ = runInBackground(
      this,
      [path = path_, first_look = first_look_](JobContext& job) {
        return first_look ? readFirstLookOrPhoto(path, job) : readPhoto(path, job);
      },
      [this](JobOutcome<LoadOutcome> outcome) {
        if (outcome.cancelled || cancelled_) {
          emit finished();
          return;
        }
        if (!outcome.value) {
          emit failed(tr("Could not load %1: %2").arg(path_, outcome.error));
        } else if (!outcome.value->photo) {
          emit failed(outcome.value->message);
        } else {
          const bool first_look = !outcome.value->photo->hasFullImage();
          emit loaded(outcome.value->photo);
          // A receiver of loaded() may have cancelled this loader (a newer open).
          if (first_look && !cancelled_) {
            if (!hold_whole_read_) {
              startWholeRead();
            } else {
              whole_read_waiting_ = true;
              QTimer::singleShot(hold_ms_, this, &ImageLoader::releaseWholeRead);
            }
            return;
          }
        }
        emit finished();
      });
  connect(job_, &BackgroundJob::progressChanged, this, &ImageLoader::progressChanged);
}

void ImageLoader::releaseWholeRead() {
  if (!whole_read_waiting_) return;
  whole_read_waiting_ = false;
  if (cancelled_) {
    emit finished();
    return;
  }
  startWholeRead();
}

void ImageLoader::startWholeRead() {
  job_ = runInBackground(
      this, [path = path_](JobContext& job) { return readPhoto(path, job); },
      [this](JobOutcome<LoadOutcome> outcome) {
        if (!outcome.cancelled && !cancelled_) {
          if (!outcome.value)
            emit refineFailed(tr("Could not load %1: %2").arg(path_, outcome.error));
          else if (outcome.value->photo)
            emit refined(outcome.value->photo);
          else
            emit refineFailed(outcome.value->message);
        }
        emit finished();
      });
  connect(job_, &BackgroundJob::progressChanged, this, &ImageLoader::progressChanged);
}

}  // namespace artcam::ui
