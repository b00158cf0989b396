// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_commands.h"

namespace artcam::ui {

SetInsertionStateCommand::SetInsertionStateCommand(InsertionModel* model, InsertionState before,
                                                   InsertionState after, const QString& text)
    : QUndoCommand(text), model_(model), before_(std::move(before)), after_(std::move(after)) {}

void SetInsertionStateCommand::undo() { model_->setState(before_); }
void SetInsertionStateCommand::redo() { model_->setState(after_); }

}  // namespace artcam::ui
