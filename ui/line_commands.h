// SPDX-License-Identifier: Apache-2.0
// Undo commands for the straight lines (document.h, LineSet). Like the pair commands they store
// the old and the new value, never a delta, so undo restores the lines and hence the fit bit
// for bit; a line set is a few dozen points, so whole values cost nothing. One command class
// carries every line edit (add point, end line, cancel, delete, move a point, clear); the push
// helpers below name the edit and are what tools and menus call. Moves of one drag share a
// gesture id and merge into one undo step; their first redo fits in the document's FitWorker.
//
// Points are photo pixels (centres at i + 0.5).
#pragma once

#include "ui/document.h"

#include <QString>
#include <QUndoCommand>

namespace artcam::ui {

inline constexpr int kMoveLinePointId = 1003;  // beside commands.h's ids
inline constexpr int kMinLinePoints = 3;       // two points are always on a line

class SetLinesCommand : public QUndoCommand {
 public:
  SetLinesCommand(Document* document, LineSet after, const QString& text, int gesture = 0);
  void redo() override;
  void undo() override;
  int id() const override { return gesture_ != 0 ? kMoveLinePointId : -1; }
  bool mergeWith(const QUndoCommand* other) override;

 private:
  Document* document_;
  LineSet before_;
  LineSet after_;
  int gesture_;
  bool pushed_ = false;  // the first redo (QUndoStack::push) has run
};

// Adds a point to the open line (starting one when none is open).
void pushAddLinePoint(Document* document, const Eigen::Vector2d& point_px);
// Ends the open line into the fitted lines. Refused (false, nothing pushed) below
// kMinLinePoints points.
bool pushEndLine(Document* document);
// Drops the open line (Esc). False when none is open.
bool pushCancelLine(Document* document);
void pushDeleteLine(Document* document, int index);
// Deletes several finished lines in one undo step (the Lines panel's Delete). False when none of
// the indices names a line.
bool pushDeleteLines(Document* document, std::vector<int> indices);
// Enables or disables finished line `index` (the Lines panel's check box): a disabled line
// stays drawn but is not fitted.
void pushSetLineEnabled(Document* document, int index, bool enabled);
// Gives the finished lines `indices` a role (horizontal, vertical or none), one undo step; a
// role does not change the fit, it is what the Lines panel measures each line's tilt against.
// False when nothing changes.
bool pushSetLineRoles(Document* document, const std::vector<int>& indices, LineRole role);
// Moves point `point` of finished line `line`; a drag passes one gesture id for all its moves.
void pushMoveLinePoint(Document* document, int line, int point, const Eigen::Vector2d& to_px,
                       int gesture);
// Removes every line, the open one too. False when there are none.
bool pushClearLines(Document* document);

// The model row's choice while lines drive the fit: the pairs' model class and the lines'
// model together (Document::setModels), one undo step.
class SetModelChoiceCommand : public QUndoCommand {
 public:
  SetModelChoiceCommand(Document* document, ModelClass model, LineModel line_model,
                        const QString& text);
  void redo() override;
  void undo() override;

 private:
  Document* document_;
  ModelClass model_before_, model_after_;
  LineModel line_before_, line_after_;
};

}  // namespace artcam::ui
