#include "ui/document.h"

#include "ui/colour/colour_stage.h"

#include <algorithm>
#include <exception>

namespace artcam::ui {
namespace {

const Block kImagePosition{BlockKind::Position, 3};

// Cameras need image frames; before a photo is open a 1×1 placeholder keeps them valid.
Camera identityCamera(FrameSize f) {
  if (!f.isImage()) f = {1, 1};
  return Camera::identity({kImagePosition}, f, f);
}

}  // namespace

Document::Document(QObject* parent) : QObject(parent) { camera_ = identityCamera({}); }

FrameSize Document::frame() const { return photo_ ? photo_->size() : FrameSize{}; }

void Document::reset(PhotoPtr photo, std::vector<Pair> pairs, ModelClass model,
                     std::optional<Camera> manual_camera) {
  undo_stack_.clear();
  photo_ = std::move(photo);
  pairs_ = std::move(pairs);
  model_ = model;
  manual_camera_ = std::move(manual_camera);
  colour_block_.reset();
  selection_.clear();
  refit();
  depth_.reset(frame());
  undo_stack_.setClean();
  emit photoChanged();
  emit pairCountChanged();
  emit pairsChanged();
  emit modelChanged();
  emit selectionChanged();
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

void Document::setPairs(const std::vector<int>& indices, const std::vector<Pair>& values) {
  const size_t n = std::min(indices.size(), values.size());
  for (size_t k = 0; k < n; ++k) {
    const int i = indices[k];
    if (i >= 0 && i < static_cast<int>(pairs_.size())) pairs_[static_cast<size_t>(i)] = values[k];
  }
  refit();
  emit pairsChanged();
  emit cameraChanged();
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

void Document::setModel(ModelClass model) {
  if (model == model_) return;
  model_ = model;
  refit();
  emit modelChanged();
  emit pairsChanged();  // residuals changed
  emit cameraChanged();
}

void Document::setManualCamera(std::optional<Camera> camera) {
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
  const ModelClass m = model_ == ModelClass::Auto ? ModelClass::Translation : model_;
  return std::max(0, minimumMatches(m) - enabledPairCount());
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

// Every edit refits (the fit is a small SVD: cheap on the GUI thread for a few hundred
// pairs). The camera is a pure function of (photo, pairs, model, manual camera), which is what
// makes undo restore it exactly.
void Document::refit() {
  const FrameSize f = frame();
  fit_ = FitSummary{};
  residual_by_pair_.assign(pairs_.size(), -1.0);
  camera_ = identityCamera(f);
  if (!f.isImage()) return;
  try {
    if (manual_camera_) {
      camera_ = *manual_camera_;
    } else if (enabledPairCount() == 0) {
      fit_.status = Status::failure("No point pairs yet: click a source point, then its target.");
    } else if (const int need = pairsNeeded(); need > 0) {
      fit_.status =
          Status::failure("Need " + std::to_string(need) + " more pair" + (need == 1 ? "" : "s") +
                          " for the " + std::string(modelClassName(model_)) + " model.");
    } else {
      FitOptions options;
      options.model = model_;
      fit_ = fitImageCamera(matches(), f, f, options);
      if (fit_.status.ok) camera_ = fit_.camera;
    }
    if (!pairs_.empty()) {
      // Residuals of every pair, disabled ones too: they show how far an outlier is off.
      std::vector<PointMatch> all = matches();
      for (PointMatch& m : all) m.enabled = true;
      const std::vector<double> r = reprojectionResiduals(camera_, all);
      for (size_t i = 0; i < r.size() && i < residual_by_pair_.size(); ++i)
        residual_by_pair_[i] = r[i];
    }
    // After the residuals: they are a property of the geometry (a position-only camera).
    if (colour_block_) camera_ = withColourBlock(camera_, *colour_block_);
  } catch (const std::exception& e) {
    // A broken contract in the engine must not take the GUI down: report it as a failed fit.
    fit_ = FitSummary{};
    fit_.status = Status::failure(std::string("Fit failed: ") + e.what());
    camera_ = identityCamera(f);
  }
}

}  // namespace artcam::ui
