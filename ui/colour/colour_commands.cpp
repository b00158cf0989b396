// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/colour_commands.h"

#include "ui/document.h"

namespace artcam::ui {

SetColourSamplesCommand::SetColourSamplesCommand(ColourSampleModel* model, ColourSampleState before,
                                                 ColourSampleState after, const QString& text,
                                                 int gesture)
    : QUndoCommand(text),
      model_(model),
      before_(std::move(before)),
      after_(std::move(after)),
      gesture_(gesture) {}

void SetColourSamplesCommand::undo() { model_->setState(before_); }
void SetColourSamplesCommand::redo() { model_->setState(after_); }

bool SetColourSamplesCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const SetColourSamplesCommand*>(other);
  if (!o || o->model_ != model_ || o->gesture_ != gesture_ || gesture_ == 0) return false;
  after_ = o->after_;
  return true;
}

SetColourBlockCommand::SetColourBlockCommand(Document* document, std::optional<Camera> colour,
                                             const QString& text)
    : QUndoCommand(text),
      document_(document),
      before_(document->colourBlock()),
      after_(std::move(colour)) {}

void SetColourBlockCommand::undo() { document_->setColourBlock(before_); }
void SetColourBlockCommand::redo() { document_->setColourBlock(after_); }

void pushColourSamples(ColourSampleModel* model, ColourSampleState after, const QString& text,
                       int gesture) {
  if (after == model->state()) return;
  model->document()->undoStack()->push(
      new SetColourSamplesCommand(model, model->state(), std::move(after), text, gesture));
}

}  // namespace artcam::ui
