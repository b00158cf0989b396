// SPDX-License-Identifier: Apache-2.0
// Connects the document to the RenderWorker: every camera or photo change becomes a render
// request with a new generation stamp; results older than the newest delivered one are
// dropped, so the preview only ever moves forward.
#pragma once

#include "ui/render_worker.h"

#include <QImage>
#include <QObject>

#include <memory>

namespace artcam::ui {

class Document;

class PreviewController : public QObject {
  Q_OBJECT

 public:
  explicit PreviewController(Document* document, QObject* parent = nullptr);
  ~PreviewController() override;

  const QImage& image() const { return image_; }  // newest warped preview
  quint64 imageGeneration() const { return image_generation_; }
  bool imageIsFinal() const { return image_final_; }
  quint64 requestedGeneration() const { return generation_; }
  double lastRenderMs() const { return last_ms_; }
  RenderWorker* worker() { return &worker_; }
  // The depth raster cameras with a depth block read (core/depth/depth_raster.h form); null:
  // none. Re-renders when the camera needs it.
  void setDepth(std::shared_ptr<const ImageF> depth);

 public slots:
  void schedule();

 signals:
  void previewChanged();
  void renderFailed(const QString& message);

 private:
  void onRendered(const QImage& image, quint64 generation, bool final_pass, double ms);

  Document* document_;
  RenderWorker worker_;
  std::shared_ptr<const ImageF> source_;  // shared with the worker; rebuilt per photo
  std::shared_ptr<const StoredEncoding> encoding_;  // how the photo's values were decoded
  std::shared_ptr<const ImageF> depth_;
  const void* source_photo_ = nullptr;
  quint64 generation_ = 0;
  QImage image_;
  quint64 image_generation_ = 0;
  bool image_final_ = false;
  double last_ms_ = 0.0;
};

}  // namespace artcam::ui
