// SPDX-License-Identifier: Apache-2.0
// Loads a photo off the GUI thread, a one-shot job of background_job.h: readImage, then the
// preview and display copies (photo.h). Progress and the result arrive on the GUI thread as
// signals; exceptions are caught by the job helper and arrive as failed(). One loader per file;
// cancel() makes the read stop at its next progress callback (then only finished() comes).
#pragma once

#include "ui/background_job.h"
#include "ui/photo.h"

#include <QObject>
#include <QPointer>
#include <QString>

namespace artcam::ui {

class ImageLoader : public QObject {
  Q_OBJECT

 public:
  explicit ImageLoader(QString path, QObject* parent = nullptr);
  ~ImageLoader() override;  // cancels the read; never waits for it

  const QString& path() const { return path_; }
  // Starts the read off the GUI thread (once).
  void start();
  void cancel();

 signals:
  void progressChanged(int percent);
  void loaded(artcam::ui::PhotoPtr photo);
  void failed(const QString& message);
  // After loaded() or failed(), or alone when cancelled.
  void finished();

 private:
  QString path_;
  QPointer<BackgroundJob> job_;
};

}  // namespace artcam::ui
