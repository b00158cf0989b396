// Loads a photo off the GUI thread (the GUI thread never blocks on I/O): readImage, then the
// preview and display copies, all in a QThread. Progress and the result arrive by queued
// signals. One loader per file; cancel() makes the read stop at its next progress callback.
#pragma once

#include "ui/photo.h"

#include <QString>
#include <QThread>

#include <atomic>

namespace artcam::ui {

class ImageLoader : public QThread {
  Q_OBJECT

 public:
  explicit ImageLoader(QString path, QObject* parent = nullptr);
  ~ImageLoader() override;  // cancels and joins

  const QString& path() const { return path_; }
  void cancel() { cancel_ = true; }

 signals:
  void progressChanged(int percent);
  void loaded(artcam::ui::PhotoPtr photo);
  void failed(const QString& message);

 protected:
  void run() override;

 private:
  QString path_;
  std::atomic<bool> cancel_{false};
};

}  // namespace artcam::ui
