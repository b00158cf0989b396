// SPDX-License-Identifier: Apache-2.0
#include "ui/commands.h"

#include <QCoreApplication>

#include <algorithm>

namespace artcam::ui {

AddPairCommand::AddPairCommand(Document* document, Pair pair, int index)
    : document_(document),
      pair_(std::move(pair)),
      index_(index < 0 ? static_cast<int>(document->pairs().size()) : index) {
  setText(QCoreApplication::translate("commands", "Add pair"));
}

void AddPairCommand::redo() { document_->insertPair(index_, pair_); }
void AddPairCommand::undo() { document_->removePair(index_); }

MovePairsCommand::MovePairsCommand(Document* document, std::vector<int> indices,
                                   std::vector<Pair> before, std::vector<Pair> after, int gesture,
                                   const QString& text)
    : document_(document),
      indices_(std::move(indices)),
      before_(std::move(before)),
      after_(std::move(after)),
      gesture_(gesture) {
  setText(text);
}

// The push of a drag's move (gesture id, first redo) fits in the worker: the GUI thread only
// records it. Undo and redo later refit at once, so camera() is exact when they return.
void MovePairsCommand::redo() {
  const bool live_move = gesture_ != 0 && !pushed_;
  pushed_ = true;
  document_->setPairs(indices_, after_,
                      live_move ? Document::Refit::InWorker : Document::Refit::Now);
}
void MovePairsCommand::undo() { document_->setPairs(indices_, before_); }

bool MovePairsCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const MovePairsCommand*>(other);
  if (!o || o->gesture_ != gesture_ || o->indices_ != indices_) return false;
  after_ = o->after_;  // keep our `before_`: one step back undoes the whole drag
  return true;
}

DeletePairsCommand::DeletePairsCommand(Document* document, std::vector<int> indices)
    : document_(document), indices_(std::move(indices)) {
  std::sort(indices_.begin(), indices_.end());
  indices_.erase(std::unique(indices_.begin(), indices_.end()), indices_.end());
  for (int i : indices_) pairs_.push_back(document_->pairs().at(static_cast<size_t>(i)));
  setText(QCoreApplication::translate("commands", "Delete %n pair(s)", nullptr,
                                      static_cast<int>(indices_.size())));
}

void DeletePairsCommand::redo() {
  // Descending, so earlier indices stay valid.
  for (auto it = indices_.rbegin(); it != indices_.rend(); ++it) document_->removePair(*it);
}

void DeletePairsCommand::undo() {
  for (size_t k = 0; k < indices_.size(); ++k) document_->insertPair(indices_[k], pairs_[k]);
  document_->setSelection(indices_);
}

SetModelCommand::SetModelCommand(Document* document, ModelClass model)
    : document_(document), before_(document->model()), after_(model) {
  setText(QCoreApplication::translate("commands", "Model: %1")
              .arg(QString::fromUtf8(modelClassName(model).data(),
                                     static_cast<qsizetype>(modelClassName(model).size()))));
}

void SetModelCommand::redo() { document_->setModel(after_); }
void SetModelCommand::undo() { document_->setModel(before_); }

SetCameraCommand::SetCameraCommand(Document* document, std::optional<Artcam> camera,
                                   const QString& text, int merge_key)
    : document_(document),
      before_(document->manualCamera()),
      after_(std::move(camera)),
      merge_key_(merge_key) {
  setText(text);
}

void SetCameraCommand::redo() { document_->setManualCamera(after_); }
void SetCameraCommand::undo() { document_->setManualCamera(before_); }

bool SetCameraCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const SetCameraCommand*>(other);
  if (!o || o->merge_key_ != merge_key_) return false;
  after_ = o->after_;
  return true;
}

SetSecondImageCommand::SetSecondImageCommand(Document* document,
                                             std::optional<Document::SecondImage> second)
    : document_(document), before_(document->secondImage()), after_(std::move(second)) {
  setText(after_ ? QObject::tr("Set Second Image") : QObject::tr("Remove Second Image"));
}

void SetSecondImageCommand::redo() { document_->setSecondImage(after_); }
void SetSecondImageCommand::undo() { document_->setSecondImage(before_); }

SetFinishCommand::SetFinishCommand(Document* document, std::string finish)
    : document_(document), before_(document->finish()), after_(std::move(finish)) {
  setText(after_.empty() ? QObject::tr("Remove Finish")
                         : QObject::tr("Finish: %1").arg(QString::fromStdString(after_)));
}

void SetFinishCommand::redo() { document_->setFinish(after_); }
void SetFinishCommand::undo() { document_->setFinish(before_); }

SetEffectsCommand::SetEffectsCommand(Document* document, std::vector<EffectStep> effects,
                                     const QString& text, int gesture)
    : document_(document), before_(document->effects()), after_(std::move(effects)),
      gesture_(gesture) {
  setText(text);
}

void SetEffectsCommand::redo() { document_->setEffects(after_); }
void SetEffectsCommand::undo() { document_->setEffects(before_); }

bool SetEffectsCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const SetEffectsCommand*>(other);
  if (!o || o->gesture_ != gesture_) return false;
  after_ = o->after_;
  return true;
}

void pushTogglePairsEnabled(Document* document, const std::vector<int>& indices) {
  if (indices.empty()) return;
  std::vector<Pair> before, after;
  for (int i : indices) {
    const Pair& p = document->pairs().at(static_cast<size_t>(i));
    before.push_back(p);
    Pair q = p;
    q.enabled = !p.enabled;
    after.push_back(q);
  }
  document->undoStack()->push(
      new MovePairsCommand(document, indices, std::move(before), std::move(after), 0,
                           QCoreApplication::translate("commands", "Toggle pair enabled")));
}

void pushDeleteSelection(Document* document) {
  if (document->selection().empty()) return;
  document->undoStack()->push(new DeletePairsCommand(document, document->selection()));
}

}  // namespace artcam::ui
