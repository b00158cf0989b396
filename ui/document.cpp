// SPDX-License-Identifier: Apache-2.0
#include "ui/document.h"

#include "ui/fit_worker.h"

#include <algorithm>
#include <exception>

namespace artcam::ui {

Document::Document(QObject* parent) : QObject(parent) {
  camera_ = identityImageCamera({});
  composeStack();
  assemble();
  // Effects that read depth join the camera when the first depth appears and leave it when the
  // last goes; other depth edits change only the raster the renderers read.
  connect(&depth_, &DepthModel::depthChanged, this, &Document::onDepthChanged);
}

Document::~Document() = default;

FrameSize Document::frame() const { return photo_ ? photo_->size() : FrameSize{}; }

bool Document::refinePhoto(PhotoPtr full) {
  if (!photo_ || !full || photo_->hasFullImage() || !full->hasFullImage() ||
      full->path != photo_->path || full->size().width != photo_->size().width ||
      full->size().height != photo_->size().height)
    return false;
  // The camera lives in normalised frames and the frame is unchanged: no refit, no new camera.
  photo_ = std::move(full);
  emit photoRefined();
  return true;
}

void Document::failRefine(const QString& message) {
  if (photo_ && !photo_->hasFullImage()) emit photoRefineFailed(message);
}

void Document::whenFullImage(QObject* context, std::function<void(bool ready)> then) {
  if (!photo_ || photo_->hasFullImage()) {
    then(true);
    return;
  }
  // One shot: whichever of the three comes first disconnects all three.
  auto links = std::make_shared<std::vector<QMetaObject::Connection>>();
  auto once = [links, then = std::move(then)](bool ready) {
    for (const QMetaObject::Connection& c : *links) QObject::disconnect(c);
    links->clear();
    then(ready);
  };
  links->push_back(connect(this, &Document::photoRefined, context, [once] { once(true); }));
  links->push_back(connect(this, &Document::photoRefineFailed, context, [once] { once(false); }));
  links->push_back(connect(this, &Document::photoChanged, context, [once] { once(false); }));
}

bool LineSet::operator==(const LineSet& o) const {
  if (open != o.open || lines.size() != o.lines.size()) return false;
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].label != o.lines[i].label || lines[i].points != o.lines[i].points ||
        lines[i].enabled != o.lines[i].enabled || lines[i].role != o.lines[i].role)
      return false;
  return true;
}

void Document::reset(PhotoPtr photo, std::vector<Pair> pairs, ModelClass model,
                     std::optional<Artcam> manual_camera, std::vector<EffectStep> effects,
                     std::vector<LineTrace> lines, LineModel line_model) {
  undo_stack_.clear();
  photo_ = std::move(photo);
  pairs_ = std::move(pairs);
  lines_ = LineSet{std::move(lines), {}};
  model_ = model;
  line_model_ = line_model;
  manual_camera_ = std::move(manual_camera);
  effects_ = std::move(effects);
  second_.reset();
  finish_.clear();
  colour_block_.reset();
  selection_.clear();
  depth_.reset(frame());
  has_depth_ = depth_.hasDepth();
  composeStack();
  refit();
  undo_stack_.setClean();
  emit photoChanged();
  emit pairCountChanged();
  emit pairsChanged();
  emit linesChanged();
  emit modelChanged();
  emit selectionChanged();
  emit effectsChanged();
  emit cameraChanged();
}

void Document::insertPair(int index, const Pair& pair) {
  index = std::clamp(index, 0, static_cast<int>(pairs_.size()));
  pairs_.insert(pairs_.begin() + index, pair);
  selection_.clear();
  refit();
  emit pairCountChanged();
  emit pairsChanged();
  emit selectionChanged();
  emit cameraChanged();
}

void Document::removePair(int index) {
  if (index < 0 || index >= static_cast<int>(pairs_.size())) return;
  pairs_.erase(pairs_.begin() + index);
  selection_.clear();
  refit();
  emit pairCountChanged();
  emit pairsChanged();
  emit selectionChanged();
  emit cameraChanged();
}

void Document::setPairs(const std::vector<int>& indices, const std::vector<Pair>& values,
                        Refit refit_mode) {
  const size_t n = std::min(indices.size(), values.size());
  for (size_t k = 0; k < n; ++k) {
    const int i = indices[k];
    if (i >= 0 && i < static_cast<int>(pairs_.size())) pairs_[static_cast<size_t>(i)] = values[k];
  }
  if (refit_mode == Refit::InWorker && fits_in_worker_) {
    refitInWorker();
    emit pairsChanged();
    return;
  }
  refit();
  emit pairsChanged();
  emit cameraChanged();
}

void Document::setLineSet(LineSet lines, Refit refit_mode) {
  const bool fitted_changed = !(LineSet{lines.lines, {}} == LineSet{lines_.lines, {}});
  lines_ = std::move(lines);
  if (!fitted_changed) {
    emit linesChanged();
    return;
  }
  if (refit_mode == Refit::InWorker && fits_in_worker_) {
    refitInWorker();
    emit linesChanged();
    return;
  }
  refit();
  emit linesChanged();
  emit pairsChanged();  // residuals changed
  emit cameraChanged();
}

std::optional<LineBow> Document::lineBow(int index) const {
  if (index < 0 || index >= static_cast<int>(lines_.lines.size()) ||
      !lines_.lines[static_cast<size_t>(index)].enabled)
    return std::nullopt;
  // The fit's bows are of the enabled lines, in order.
  const auto enabled_before = std::count_if(lines_.lines.begin(), lines_.lines.begin() + index,
                                            [](const LineTrace& l) { return l.enabled; });
  if (enabled_before >= static_cast<long>(line_bows_.size())) return std::nullopt;
  return line_bows_[static_cast<size_t>(enabled_before)];
}

// A drag's move: a fit per mouse move (a few hundred pairs, or a line fit's iterations) would
// stall the GUI thread, so only the edit is recorded here; camera, fit, residuals and bows
// follow from the worker.
void Document::refitInWorker() {
  ++edit_revision_;
  if (!fit_worker_) {
    fit_worker_ = std::make_unique<FitWorker>([this](FittedCamera fitted, quint64 revision) {
      onWorkerFit(std::move(fitted), revision);
    });
    // fitDocumentCamera turns the engine's exceptions into a failed fit; anything else the
    // worker reports would leave fitPending() true with no fit on its way, so the newest
    // revision is fitted here instead (its inputs are still fitInputs()).
    connect(
        fit_worker_.get(), &FitWorker::failed, this,
        [this](const QString&, quint64 revision) {
          if (revision == edit_revision_) onWorkerFit(fitDocumentCamera(fitInputs()), revision);
        },
        Qt::QueuedConnection);
  }
  fit_worker_->request({fitInputs(), edit_revision_});
}

int Document::enabledPairCount() const {
  return static_cast<int>(
      std::count_if(pairs_.begin(), pairs_.end(), [](const Pair& p) { return p.enabled; }));
}

std::vector<PointMatch> Document::matches() const {
  std::vector<PointMatch> out;
  out.reserve(pairs_.size());
  for (const Pair& p : pairs_) out.push_back({p.source, p.target, p.enabled});
  return out;
}

void Document::setModel(ModelClass model) { setModels(model, line_model_); }

void Document::setModels(ModelClass model, LineModel line_model) {
  if (model == model_ && line_model == line_model_) return;
  model_ = model;
  line_model_ = line_model;
  refit();
  emit modelChanged();
  emit pairsChanged();  // residuals changed
  emit cameraChanged();
}

void Document::setEffects(std::vector<EffectStep> effects) {
  effects_ = std::move(effects);
  composeStack();
  assemble();
  emit effectsChanged();
  emit cameraChanged();
}

void Document::setSecondImage(std::optional<SecondImage> second) {
  second_ = std::move(second);
  composeStack();
  assemble();
  emit secondImageChanged();
  emit cameraChanged();
}

void Document::setFinish(std::string finish) {
  if (finish == finish_) return;
  finish_ = std::move(finish);
  emit finishChanged();
}

void Document::onDepthChanged() {
  if (depth_.hasDepth() == has_depth_) return;
  has_depth_ = depth_.hasDepth();
  composeStack();
  assemble();
  emit cameraChanged();
}

void Document::setManualCamera(std::optional<Artcam> camera) {
  manual_camera_ = std::move(camera);
  refit();
  emit pairsChanged();
  emit cameraChanged();
}

void Document::setColourBlock(std::optional<Camera> colour) {
  colour_block_ = std::move(colour);
  refit();
  emit cameraChanged();
}

int Document::pairsNeeded() const {
  // Enabled lines determine the geometry on their own (pairs only join them).
  if (std::any_of(lines_.lines.begin(), lines_.lines.end(),
                  [](const LineTrace& l) { return l.enabled; }))
    return 0;
  return pairsNeededFor(model_, enabledPairCount());
}

double Document::residual(int index) const {
  if (index < 0 || index >= static_cast<int>(residual_by_pair_.size())) return -1.0;
  return residual_by_pair_[static_cast<size_t>(index)];
}

bool Document::isSelected(int index) const {
  return std::binary_search(selection_.begin(), selection_.end(), index);
}

void Document::setSelection(std::vector<int> indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::erase_if(indices, [&](int i) { return i < 0 || i >= static_cast<int>(pairs_.size()); });
  if (indices == selection_) return;
  selection_ = std::move(indices);
  emit selectionChanged();
}

bool Document::linesDriveFit() const {
  return !manual_camera_ && std::any_of(lines_.lines.begin(), lines_.lines.end(),
                                        [](const LineTrace& l) { return l.enabled; });
}

FitInputs Document::fitInputs() const {
  std::optional<Camera> manual;
  if (manual_camera_) manual = manual_camera_->main();
  return {frame(), matches(), lines_.lines, model_, manual, colour_block_, line_model_};
}

void Document::applyFit(FittedCamera fitted) {
  fit_ = std::move(fitted.fit);
  camera_ = std::move(fitted.camera);
  residual_by_pair_ = std::move(fitted.residual_by_pair);
  line_bows_ = std::move(fitted.line_bows);
  assemble();
}

void Document::composeStack() {
  const FrameSize f = frame().isImage() ? frame() : FrameSize{1, 1};
  stack_ = composeEffectStack(effects_, f, has_depth_, second_.has_value());
}

void Document::assemble() {
  std::string base_note;
  Artcam base(camera_);
  try {
    base = documentBase(manual_camera_, camera_, colour_block_, &base_note);
  } catch (const std::exception& e) {
    base_note = std::string("the colour block could not be added to every layer: ") + e.what();
  }
  // Every refit passes here (a drag's worker fits too): only the cheap join with the stack.
  whole_ = assembleDocumentArtcam(base, stack_);
  if (!base_note.empty()) whole_.note = base_note + (whole_.note.empty() ? "" : "; " + whole_.note);
}

// Discrete edits refit on the GUI thread (a small SVD for a few pairs, and camera() is then
// exact when the edit returns); a newer revision drops any worker fit still on its way.
void Document::refit() {
  ++edit_revision_;
  applyFit(fitDocumentCamera(fitInputs()));
  camera_revision_ = edit_revision_;
}

void Document::onWorkerFit(FittedCamera fitted, quint64 revision) {
  if (revision != edit_revision_) return;  // a newer edit exists: its own fit is coming
  applyFit(std::move(fitted));
  camera_revision_ = revision;
  emit pairsChanged();  // residuals changed
  emit linesChanged();  // bows changed
  emit cameraChanged();
}

}  // namespace artcam::ui
