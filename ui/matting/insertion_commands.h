// SPDX-License-Identifier: Apache-2.0
// The one undo command of Insertion mode (every edit a QUndoCommand storing old and new
// values, never deltas): the whole InsertionState before and after, so undo restores it
// bit-exactly. A state is small (a few hundred matches, a shared graphic pointer).
#pragma once

#include "ui/matting/insertion_model.h"

#include <QUndoCommand>

namespace artcam::ui {

class SetInsertionStateCommand : public QUndoCommand {
 public:
  SetInsertionStateCommand(InsertionModel* model, InsertionState before, InsertionState after,
                           const QString& text);
  void undo() override;
  void redo() override;

 private:
  InsertionModel* model_;
  InsertionState before_;
  InsertionState after_;
};

}  // namespace artcam::ui
