// Full-resolution export of the warped photo in a worker thread: core's render front door
// (core/pipeline/render.h) on the original pixels with progress and cancel (polled between
// tiles), then writeImage with the photo's format and metadata (atomic). Results come back by
// queued signals; exceptions stop here. The front door picks the same path as the preview does
// (colour/depth cameras through the attributed renderer), so a fitted colour block is in the
// exported file as it is in the preview.
#pragma once

#include "core/model/camera.h"
#include "ui/photo.h"

#include <QString>
#include <QThread>

#include <atomic>
#include <memory>

namespace artcam::ui {

class ExportJob : public QThread {
  Q_OBJECT

 public:
  ExportJob(PhotoPtr photo, Camera camera, QString path, QObject* parent = nullptr);
  ~ExportJob() override;  // cancels and joins

  void cancel() { cancel_ = true; }
  // The depth block's input for cameras that read depth (before start()).
  void setDepth(std::shared_ptr<const ImageF> depth) { depth_ = std::move(depth); }

 signals:
  void progressChanged(int percent);
  // ok false: message says why (or that it was cancelled).
  void done(bool ok, const QString& message);

 protected:
  void run() override;

 private:
  PhotoPtr photo_;
  Camera camera_;
  QString path_;
  std::shared_ptr<const ImageF> depth_;
  std::atomic<bool> cancel_{false};
};

}  // namespace artcam::ui
