// SPDX-License-Identifier: Apache-2.0
// The colour dock's undo commands (every edit a QUndoCommand storing old and new
// values, never deltas, so undo restores the state bit-exactly):
// - SetColourSamplesCommand: the whole ColourSampleState before and after (add, delete, move,
//   enable, radius, reference photo); drags of one gesture merge into one step;
// - SetColourBlockCommand: the document's colour block before and after (a fit, or clearing it).
#pragma once

#include "core/model/camera.h"
#include "ui/colour/colour_samples.h"

#include <QUndoCommand>

#include <optional>

namespace artcam::ui {

class Document;

enum ColourCommandId { kMoveColourSampleId = 1201 };

class SetColourSamplesCommand : public QUndoCommand {
 public:
  // A non-zero `gesture` merges consecutive commands of the same gesture (one drag, one step).
  SetColourSamplesCommand(ColourSampleModel* model, ColourSampleState before,
                          ColourSampleState after, const QString& text, int gesture = 0);
  void undo() override;
  void redo() override;
  int id() const override { return gesture_ != 0 ? kMoveColourSampleId : -1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  ColourSampleModel* model_;
  ColourSampleState before_;
  ColourSampleState after_;
  int gesture_;
};

class SetColourBlockCommand : public QUndoCommand {
 public:
  SetColourBlockCommand(Document* document, std::optional<Camera> colour, const QString& text);
  void undo() override;
  void redo() override;

 private:
  Document* document_;
  std::optional<Camera> before_;
  std::optional<Camera> after_;
};

// Pushes a SetColourSamplesCommand from the model's current state to `after` (nothing when
// equal) on the document's undo stack.
void pushColourSamples(ColourSampleModel* model, ColourSampleState after, const QString& text,
                       int gesture = 0);

}  // namespace artcam::ui
