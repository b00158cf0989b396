// SPDX-License-Identifier: Apache-2.0
// Loads a photo off the GUI thread, one-shot jobs of background_job.h: readImage, then the
// preview and display copies (photo.h). Progress and the result arrive on the GUI thread as
// signals; exceptions are caught by the job helper and arrive as failed(). One loader per file;
// cancel() makes the read stop at its next progress callback (then only finished() comes).
//
// First look (setFirstLook, the studio's photo opens): a JPEG that has one (core/io/first_look.h:
// sRGB, no ICC conversion) is first read through libjpeg's DCT scaling, just large enough for
// the live preview (kLivePreviewMaxWidth × kLivePreviewMaxHeight), and loaded() brings that
// first look (Photo::reduced_by > 1, no full pixels, size() the whole photo's). Then a second
// job reads the whole file and refined() brings the full photo, or refineFailed() says why
// not. The second starts when the first is delivered, so the whole read does not compete with
// the first look for the cores; with setHoldWholeRead it waits, too, until releaseWholeRead()
// (the studio calls it when the first look's preview is shown: running beside that render, the
// whole read, a second of decoding and copying, added about 15 ms to it on a 24 MP photo), or
// a quarter of a second at the latest. Any other file is read whole and only loaded()
// comes.
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
  // Before start(): read a JPEG reduced first, the whole file after (see the top).
  void setFirstLook(bool on) { first_look_ = on; }
  // Before start(): after a first look, the whole read waits for releaseWholeRead(), or
  // `at_most_ms` (a preview that never comes must not keep the full photo away).
  static constexpr int kWholeReadHoldMs = 250;
  void setHoldWholeRead(bool on, int at_most_ms = kWholeReadHoldMs) {
    hold_whole_read_ = on;
    hold_ms_ = at_most_ms;
  }
  // Starts the read off the GUI thread (once).
  void start();
  void cancel();
  // Starts a held whole read now; nothing when none is waiting (before the first look is
  // delivered, or after the whole read started).
  void releaseWholeRead();

 signals:
  // Percent of the first read (the photo shown), then of the whole read after a first look.
  void progressChanged(int percent);
  void loaded(artcam::ui::PhotoPtr photo);
  // After a first look's loaded(): the full photo, same path and size().
  void refined(artcam::ui::PhotoPtr photo);
  void refineFailed(const QString& message);
  void failed(const QString& message);
  // After the last of loaded(), refined(), refineFailed() or failed(), or alone when cancelled.
  void finished();

 private:
  void startWholeRead();

  QString path_;
  bool first_look_ = false;
  bool hold_whole_read_ = false;
  int hold_ms_ = kWholeReadHoldMs;
  bool whole_read_waiting_ = false;
  bool cancelled_ = false;
  QPointer<BackgroundJob> job_;
};

}  // namespace artcam::ui
