// SPDX-License-Identifier: Apache-2.0
// Full-resolution export of the warped photo, a one-shot job of background_job.h: the render on
// the original pixels with progress and cancel (polled between tiles), then writeImage with the
// photo's format and metadata (atomic). The outcome comes back on the GUI thread as done();
// exceptions are caught by the job helper and become the message.
// The render goes through core's render front door (core/pipeline/render.h), which picks the
// same path as the preview does (colour/depth cameras through the attributed renderer), so a
// fitted colour block is in the exported file as it is in the preview.
#pragma once

#include "core/project/project_render.h"
#include "core/pipeline/render.h"
#include "ui/background_job.h"
#include "ui/photo.h"

#include <QObject>
#include <QPointer>
#include <QString>

#include <functional>
#include <memory>

namespace artcam::ui {

class ExportJob : public QObject {
  Q_OBJECT

 public:
  ExportJob(PhotoPtr photo, Artcam camera, QString path, ExportOptions options = {},
            QObject* parent = nullptr);
  ~ExportJob() override;  // cancels the render; never waits for it

  // The depth block's input for cameras that read depth (before start()).
  void setDepth(std::shared_ptr<const ImageF> depth) { depth_ = std::move(depth); }
  // The second image compositing cameras read (before start()).
  void setSecond(std::shared_ptr<const ImageF> second) { second_ = std::move(second); }
  // Starts the export off the GUI thread (once).
  void start();
  void cancel();

  // The render of an export: core's renderExport (core/project/project_render.h), the function
  // `artcam export` calls too. `progress` is polled between tiles (false cancels).
  static ImageF render(const LoadedImage& photo, const ImageF* depth, const Artcam& camera,
                       const ExportOptions& options, const std::function<bool(double)>& progress,
                       RenderSummary* summary, const ImageF* second = nullptr);
  // The status line of a finished export: "Wrote PATH: 600×400, opaque; 1234 pixels without a
  // preimage filled (gather warp, 80 ms)".
  static QString writtenText(const QString& path, const ImageF& out, const RenderSummary& summary);

 signals:
  void progressChanged(int percent);
  // ok false: message says why (or that it was cancelled).
  void done(bool ok, const QString& message);
  // After done(), whatever the outcome.
  void finished();

 private:
  PhotoPtr photo_;
  Artcam camera_;
  ExportOptions options_;
  QString path_;
  std::shared_ptr<const ImageF> depth_;
  std::shared_ptr<const ImageF> second_;
  QPointer<BackgroundJob> job_;
};

}  // namespace artcam::ui
