// SPDX-License-Identifier: Apache-2.0
#include "ui/preview_controller.h"

#include "core/io/image_io.h"
#include "core/pipeline/render.h"
#include "ui/depth_model.h"
#include "ui/document.h"

namespace artcam::ui {


PreviewController::PreviewController(Document* document, QObject* parent)
    : QObject(parent), document_(document) {
  connect(document_, &Document::cameraChanged, this, &PreviewController::schedule);
  // The same camera over the full photo's copies; the first look's picture stays up until the
  // new one arrives, so the swap shows no gap.
  connect(document_, &Document::photoRefined, this, &PreviewController::schedule);
  connect(document_, &Document::finishChanged, this, &PreviewController::schedule);
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

void PreviewController::setDepth(std::shared_ptr<const ImageF> depth) {
  if (depth == depth_) return;
  depth_ = std::move(depth);
  if (readsDepth(document_->artcam())) schedule();
}

void PreviewController::schedule() {
  const PhotoPtr& photo = document_->photo();
  ++generation_;
  if (!photo) {
    source_.reset();
    encoding_.reset();
    source_photo_ = nullptr;
    image_ = QImage();
    image_generation_ = generation_;
    emit previewChanged();
    return;
  }
  if (source_photo_ != photo.get()) {
    // Alias the photo's preview copy: no pixel copy, and it lives as long as the worker needs.
    source_ = std::shared_ptr<const ImageF>(photo, &photo->preview);
    encoding_ = std::make_shared<const StoredEncoding>(storedEncodingOf(photo->full.info));
    source_photo_ = photo.get();
  }
  RenderRequest request;
  request.source = source_;
  request.encoding = encoding_;
  request.camera = document_->artcam();
  request.stored_orientation = photo->full.info.stored_orientation;
  // A camera that reads depth waits for the depth raster while the document has depth: the
  // raster comes through the overlay's throttled update a moment after the camera (opening a
  // project sets both), and a pass without it fails with "this camera reads depth", shown in the
  // status bar though the next pass succeeds. setDepth schedules again when the raster arrives.
  if (!depth_ && readsDepth(request.camera) && document_->depth()->hasDepth()) return;
  // Colour (or depth) changing cameras render from the float preview copy at its own size, so
  // a colour-only camera takes core's no-resampling path; geometry-only ones use the pyramid.
  const bool attributed = needsLinearPhoto(request.camera);
  // The pyramid aliases the photo, which keeps the levels' base image alive.
  if (photo->pyramid && !attributed)
    request.pyramid = std::shared_ptr<const StoredMipPyramid>(photo, photo->pyramid.get());
  if (attributed) request.depth = depth_;
  if (attributed && document_->secondImage()) request.second = document_->secondImage()->image;
  request.finish = document_->finish();
  const FrameSize size = request.pyramid
                             ? livePreviewSize(*photo)
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
