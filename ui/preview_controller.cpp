#include "ui/preview_controller.h"

#include "ui/document.h"

namespace artcam::ui {

PreviewController::PreviewController(Document* document, QObject* parent)
    : QObject(parent), document_(document) {
  connect(document_, &Document::cameraChanged, this, &PreviewController::schedule);
  // Document::reset emits cameraChanged too, so a new photo is covered.
  // Queued: the worker emits from its own thread; values cross by copy.
  connect(&worker_, &RenderWorker::rendered, this, &PreviewController::onRendered,
          Qt::QueuedConnection);
  connect(
      &worker_, &RenderWorker::failed, this,
      [this](const QString& message, quint64) { emit renderFailed(message); },
      Qt::QueuedConnection);
}

PreviewController::~PreviewController() { worker_.shutdown(); }

void PreviewController::schedule() {
  const PhotoPtr& photo = document_->photo();
  ++generation_;
  if (!photo) {
    source_.reset();
    source_photo_ = nullptr;
    image_ = QImage();
    image_generation_ = generation_;
    emit previewChanged();
    return;
  }
  if (source_photo_ != photo.get()) {
    // Alias the photo's preview copy: no pixel copy, and it lives as long as the worker needs.
    source_ = std::shared_ptr<const ImageF>(photo, &photo->preview);
    source_photo_ = photo.get();
  }
  RenderRequest request;
  request.source = source_;
  // The pyramid aliases the photo, which keeps the levels' base image alive.
  if (photo->pyramid) request.pyramid = std::shared_ptr<const StoredMipPyramid>(photo, photo->pyramid.get());
  request.camera = document_->camera();
  const FrameSize size = photo->pyramid ? livePreviewSize(*photo)
                                        : FrameSize{photo->preview.width, photo->preview.height};
  request.width = size.width;
  request.height = size.height;
  request.generation = generation_;
  worker_.request(std::move(request));
}

void PreviewController::onRendered(const QImage& image, quint64 generation, bool final_pass,
                                   double ms) {
  if (generation < image_generation_) return;
  if (generation == image_generation_ && image_final_ && !final_pass) return;
  image_ = image;
  image_generation_ = generation;
  image_final_ = final_pass;
  last_ms_ = ms;
  emit previewChanged();
}

}  // namespace artcam::ui
