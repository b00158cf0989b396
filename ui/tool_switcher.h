// SPDX-License-Identifier: Apache-2.0
// The canvas's tools as one exclusive group of checkable actions (menus and the main toolbar
// show the same actions, so the checked one is the active tool wherever it is looked at), a
// permanent status-bar label naming the canvas's active tool, and the rule that a new photo or
// project starts on the default tool (the pair tool): a tool of the previous photo (e.g. the
// Insertion region tool) would otherwise turn the first clicks on the new photo into region
// corners instead of pairs.
#pragma once

#include <QObject>

class QAction;
class QActionGroup;
class QLabel;
class QWidget;

namespace artcam::ui {

class Canvas;
class Document;

class ToolSwitcher : public QObject {
  Q_OBJECT

 public:
  // The label is a child of `window`, for its status bar.
  ToolSwitcher(Canvas* canvas, Document* document, QWidget* window);

  QActionGroup* group() const { return group_; }
  QLabel* label() const { return label_; }
  // Makes `action` checkable and one of the group; its own triggered() sets the tool.
  // `is_default`: the tool a new photo returns to.
  void addAction(QAction* action, bool is_default = false);
  QAction* defaultAction() const { return default_; }

 private:
  void updateLabel();

  Canvas* canvas_;
  QActionGroup* group_;
  QLabel* label_;
  QAction* default_ = nullptr;
};

}  // namespace artcam::ui
