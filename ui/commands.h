// SPDX-License-Identifier: Apache-2.0
// Every document edit is a QUndoCommand (after Qt's undoframework example). Commands
// store old and new values, never deltas, so undo restores state bit-exactly; the document
// refits from that state. Drags push one MovePairsCommand per mouse move and merge them
// (mergeWith) into one step per gesture; those pushes fit in the document's FitWorker.
#pragma once

#include "core/fit/fit_image.h"
#include "ui/document.h"

#include <QUndoCommand>

#include <optional>
#include <vector>

namespace artcam::ui {

enum CommandId { kMovePairsId = 1001, kEditEffectsId = 1002 };

class AddPairCommand : public QUndoCommand {
 public:
  AddPairCommand(Document* document, Pair pair, int index = -1);  // -1: append
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  Pair pair_;
  int index_;
};

// Changes several pairs at once (moves, table edits, enable toggles). Consecutive commands
// with the same non-zero `gesture` and the same indices merge into one undo step.
class MovePairsCommand : public QUndoCommand {
 public:
  MovePairsCommand(Document* document, std::vector<int> indices, std::vector<Pair> before,
                   std::vector<Pair> after, int gesture, const QString& text);
  void redo() override;
  void undo() override;
  int id() const override { return gesture_ != 0 ? kMovePairsId : -1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  std::vector<int> indices_;
  std::vector<Pair> before_;
  std::vector<Pair> after_;
  int gesture_;
  bool pushed_ = false;  // the first redo (QUndoStack::push) has run
};

class DeletePairsCommand : public QUndoCommand {
 public:
  DeletePairsCommand(Document* document, std::vector<int> indices);
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  std::vector<int> indices_;  // ascending
  std::vector<Pair> pairs_;
};

class SetModelCommand : public QUndoCommand {
 public:
  SetModelCommand(Document* document, ModelClass model);
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  ModelClass before_;
  ModelClass after_;
};

// Sets or clears the hand-made camera (tensor edits, .artcam import). Tensor edits of the same
// entry in a row merge.
class SetCameraCommand : public QUndoCommand {
 public:
  SetCameraCommand(Document* document, std::optional<Artcam> camera, const QString& text,
                   int merge_key = 0);
  void redo() override;
  void undo() override;
  int id() const override { return merge_key_ != 0 ? merge_key_ : -1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  std::optional<Artcam> before_;
  std::optional<Artcam> after_;
  int merge_key_;
};

// Replaces the effect stack (add, remove, reorder, a parameter edit). Parameter edits of one
// spin-box gesture share a non-zero `gesture` and merge into one undo step.
// Sets or removes the second image the compositing effects read.
class SetSecondImageCommand : public QUndoCommand {
 public:
  SetSecondImageCommand(Document* document, std::optional<Document::SecondImage> second);
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  std::optional<Document::SecondImage> before_;
  std::optional<Document::SecondImage> after_;
};

// Sets the finish (the marks after the render), "" for none.
class SetFinishCommand : public QUndoCommand {
 public:
  SetFinishCommand(Document* document, std::string finish);
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  std::string before_;
  std::string after_;
};

class SetEffectsCommand : public QUndoCommand {
 public:
  SetEffectsCommand(Document* document, std::vector<EffectStep> effects, const QString& text,
                    int gesture = 0);
  void redo() override;
  void undo() override;
  int id() const override { return gesture_ != 0 ? kEditEffectsId : -1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  std::vector<EffectStep> before_;
  std::vector<EffectStep> after_;
  int gesture_;
};

// Helpers the tools and panels use so they never build commands by hand.
void pushTogglePairsEnabled(Document* document, const std::vector<int>& indices);
void pushDeleteSelection(Document* document);

}  // namespace artcam::ui
