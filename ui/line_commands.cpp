// SPDX-License-Identifier: Apache-2.0
#include "ui/line_commands.h"

#include <QCoreApplication>

#include <algorithm>
#include <string>

namespace artcam::ui {
namespace {

QString tr(const char* text) { return QCoreApplication::translate("LineCommands", text); }

// A new line's label: one more than the largest numeric label, so labels stay unique (they
// name lines in messages and in the project) after deletions.
std::string nextLabel(const std::vector<LineTrace>& lines) {
  long largest = 0;
  for (const LineTrace& l : lines) {
    if (l.label.empty() || !std::all_of(l.label.begin(), l.label.end(),
                                        [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    if (l.label.size() < 10) largest = std::max(largest, std::stol(l.label));
  }
  return std::to_string(largest + 1);
}

}  // namespace

SetLinesCommand::SetLinesCommand(Document* document, LineSet after, const QString& text,
                                 int gesture)
    : document_(document), before_(document->lineSet()), after_(std::move(after)),
      gesture_(gesture) {
  setText(text);
}

void SetLinesCommand::redo() {
  const bool live_move = gesture_ != 0 && !pushed_;
  pushed_ = true;
  document_->setLineSet(after_, live_move ? Document::Refit::InWorker : Document::Refit::Now);
}

void SetLinesCommand::undo() { document_->setLineSet(before_); }

bool SetLinesCommand::mergeWith(const QUndoCommand* other) {
  const auto* o = dynamic_cast<const SetLinesCommand*>(other);
  if (!o || o->gesture_ != gesture_) return false;
  after_ = o->after_;  // keep our `before_`: one step back undoes the whole drag
  return true;
}

void pushAddLinePoint(Document* document, const Eigen::Vector2d& point_px) {
  LineSet next = document->lineSet();
  next.open.push_back(point_px);
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), tr("Add line point")));
}

bool pushEndLine(Document* document) {
  if (static_cast<int>(document->openLine().size()) < kMinLinePoints) return false;
  LineSet next = document->lineSet();
  next.lines.push_back(LineTrace{nextLabel(next.lines), std::move(next.open), true});
  next.open.clear();
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), tr("End line")));
  return true;
}

bool pushCancelLine(Document* document) {
  if (document->openLine().empty()) return false;
  LineSet next = document->lineSet();
  next.open.clear();
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), tr("Cancel line")));
  return true;
}

void pushDeleteLine(Document* document, int index) {
  if (index < 0 || index >= static_cast<int>(document->lines().size())) return;
  LineSet next = document->lineSet();
  next.lines.erase(next.lines.begin() + index);
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), tr("Delete line")));
}

void pushMoveLinePoint(Document* document, int line, int point, const Eigen::Vector2d& to_px,
                       int gesture) {
  if (line < 0 || line >= static_cast<int>(document->lines().size())) return;
  LineSet next = document->lineSet();
  std::vector<Eigen::Vector2d>& points = next.lines[static_cast<size_t>(line)].points;
  if (point < 0 || point >= static_cast<int>(points.size())) return;
  points[static_cast<size_t>(point)] = to_px;
  document->undoStack()->push(
      new SetLinesCommand(document, std::move(next), tr("Move line point"), gesture));
}

bool pushDeleteLines(Document* document, std::vector<int> indices) {
  const int count = static_cast<int>(document->lines().size());
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::erase_if(indices, [count](int i) { return i < 0 || i >= count; });
  if (indices.empty()) return false;
  LineSet next = document->lineSet();
  for (auto it = indices.rbegin(); it != indices.rend(); ++it)
    next.lines.erase(next.lines.begin() + *it);
  const QString text = indices.size() == 1 ? tr("Delete line") : tr("Delete lines");
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), text));
  return true;
}

void pushSetLineEnabled(Document* document, int index, bool enabled) {
  if (index < 0 || index >= static_cast<int>(document->lines().size())) return;
  LineSet next = document->lineSet();
  LineTrace& line = next.lines[static_cast<size_t>(index)];
  if (line.enabled == enabled) return;
  line.enabled = enabled;
  document->undoStack()->push(new SetLinesCommand(
      document, std::move(next), enabled ? tr("Enable line") : tr("Disable line")));
}

bool pushSetLineRoles(Document* document, const std::vector<int>& indices, LineRole role) {
  LineSet next = document->lineSet();
  bool changed = false;
  for (int i : indices) {
    if (i < 0 || i >= static_cast<int>(next.lines.size())) continue;
    LineTrace& line = next.lines[static_cast<size_t>(i)];
    changed = changed || line.role != role;
    line.role = role;
  }
  if (!changed) return false;
  document->undoStack()->push(new SetLinesCommand(document, std::move(next), tr("Line role")));
  return true;
}

bool pushClearLines(Document* document) {
  if (document->lines().empty() && document->openLine().empty()) return false;
  document->undoStack()->push(new SetLinesCommand(document, LineSet{}, tr("Clear lines")));
  return true;
}

SetModelChoiceCommand::SetModelChoiceCommand(Document* document, ModelClass model,
                                             LineModel line_model, const QString& text)
    : document_(document),
      model_before_(document->model()),
      model_after_(model),
      line_before_(document->lineModel()),
      line_after_(line_model) {
  setText(text);
}

void SetModelChoiceCommand::redo() { document_->setModels(model_after_, line_after_); }
void SetModelChoiceCommand::undo() { document_->setModels(model_before_, line_before_); }

}  // namespace artcam::ui
