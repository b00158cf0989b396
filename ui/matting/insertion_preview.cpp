// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_preview.h"

#include "ui/document.h"
#include "ui/matting/insertion_model.h"

namespace artcam::ui {

InsertionPreview::InsertionPreview(InsertionModel* model, QObject* parent)
    : QObject(parent), model_(model), worker_(new InsertionWorker(this)) {
  connect(worker_, &InsertionWorker::fitted, this, &InsertionPreview::onFitted,
          Qt::QueuedConnection);
  connect(worker_, &InsertionWorker::rendered, this, &InsertionPreview::onRendered,
          Qt::QueuedConnection);
  connect(
      worker_, &InsertionWorker::failed, this,
      [this](const QString& m, quint64 g) {
        if (g < fit_generation_) return;
        // The request is answered (with no camera), so the panel stops saying "Fitting…".
        fit_ = InsertionFit{};
        fit_.message = m;
        fit_generation_ = g;
        composite_ = QImage();
        composite_generation_ = g;
        emit fitChanged();
        emit compositeChanged();
        if (g == requested_) emit failed(m);
      },
      Qt::QueuedConnection);
  connect(model_, &InsertionModel::stateChanged, this, &InsertionPreview::refresh);
  connect(model_->document(), &Document::photoChanged, this, &InsertionPreview::refresh);
  connect(model_->document(), &Document::photoRefined, this, &InsertionPreview::refresh);
}

InsertionPreview::~InsertionPreview() { shutdown(); }

void InsertionPreview::shutdown() {
  stopped_ = true;
  worker_->shutdown();
}

bool InsertionPreview::isCurrent() const {
  return fit_generation_ == requested_ &&
         (!requested_renders_ || !fit_.rendersAny() || composite_generation_ == requested_);
}

void InsertionPreview::refresh() {
  if (stopped_) return;
  const InsertionState& s = model_->state();
  InsertionRequest r;
  r.generation = ++requested_;
  r.matches = model_->pointMatches();
  r.table_matches = model_->tableMatches();
  r.board_size = s.board_size;
  r.options.max_error_px = s.max_error_px;
  r.graphic = s.graphic;
  r.region = s.region;
  r.placement = s.placement;
  r.current_medium = s.current_medium;
  for (const InsertionMedium& medium : s.other_media) {
    InsertionRequest::Medium m;
    for (const GridMatch& g : medium.matches) {
      PointMatch p;
      p.source = g.board;
      p.target = g.photo;
      (g.on_table ? m.table_matches : m.matches).push_back(std::move(p));
    }
    m.region = medium.region;
    r.other_media.push_back(std::move(m));
  }
  if (const PhotoPtr& photo = model_->document()->photo()) {
    r.photo_size = photo->size();
    // The preview copy (≤ kPreviewMaxSide): the GUI shows it scaled to the photo anyway, and
    // a full-resolution render per edit would be slow on real photos; export uses the full one.
    r.photo = std::shared_ptr<const ImageF>(photo, &photo->preview);
  }
  requested_renders_ = r.photo && r.graphic;
  bool any_matches = !r.matches.empty();
  for (const InsertionRequest::Medium& m : r.other_media)
    any_matches = any_matches || !m.matches.empty();
  if (!any_matches || !r.photo) {
    // Nothing to fit: say so at once rather than asking the worker.
    fit_ = InsertionFit{};
    fit_.message = r.photo ? tr("No grid matches yet: import a grid CSV or click corners.")
                           : tr("Open a photo first.");
    fit_generation_ = requested_;
    composite_ = QImage();
    composite_generation_ = requested_;
    emit fitChanged();
    emit compositeChanged();
    return;
  }
  worker_->request(std::move(r));
  emit requested();
}

void InsertionPreview::onFitted(const InsertionFit& fit, quint64 generation) {
  if (generation < fit_generation_) return;
  fit_ = fit;
  fit_generation_ = generation;
  if (generation == requested_ && (!requested_renders_ || !fit.rendersAny())) {
    composite_ = QImage();
    composite_generation_ = generation;
    emit compositeChanged();
  }
  emit fitChanged();
}

void InsertionPreview::onRendered(const QImage& image, quint64 generation) {
  if (generation < composite_generation_) return;
  composite_ = image;
  composite_generation_ = generation;
  emit compositeChanged();
}

}  // namespace artcam::ui
