// SPDX-License-Identifier: Apache-2.0
// The effects panel: the document's effect stack (Document::effects, core/project/
// document_camera.h). Add any effect of the one effects table (core/effects/effect_table.h),
// remove or reorder entries, and set the selected entry's parameters. The parameter rows are
// made from the effect's row of the table: one spin box per number (a row of N for a vector
// parameter), its range, default and unit (as the suffix), and a slider beside each number
// that is not a named choice (named NAME/slider or NAME[i]/slider), over the same range.
//
// Decisions:
// - The panel renders nothing itself: the stack is part of the document's camera, so the main
//   canvas preview, the export, Export Camera and the saved project all show it — one render
//   path, no second thumbnail that could disagree with the export.
// - Every change is an undo command (SetEffectsCommand); the spin-box edits of one entry's
//   parameter in a row merge into one step, so a slider-like drag undoes at once.
// - The status line says which effects are in the camera and, for one left out, why (an
//   effect that reads depth waits for painted planes with three depths or a depth map).
#pragma once

#include "core/effects/effect_table.h"

#include <QWidget>

#include <map>
#include <string>
#include <vector>

class QComboBox;
class QFormLayout;
class QLabel;
class QListWidget;
class QDoubleSpinBox;

namespace artcam::ui {

class Document;

class EffectsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit EffectsPanel(Document* document, QWidget* parent = nullptr);
  ~EffectsPanel() override;

  // Appends effect `name` with the table's defaults and selects it; false for an unknown name.
  bool addEffect(const QString& name);
  void removeSelected();
  void moveSelected(int delta);  // -1 up, +1 down
  int selectedIndex() const;     // -1: none
  void setSelectedIndex(int index);

  // The selected entry's parameters as its spin boxes show them. The spin boxes are named NAME,
  // or NAME[i] for a vector's component i; setParameter types into them (false for an unknown
  // name or a vector of the wrong size).
  EffectValues parameters() const;
  bool setParameter(const QString& name, double value);
  bool setParameter(const QString& name, const std::vector<double>& value);

  QString status() const;

  // The finish row: marks after the render ("" none, or a name of core/effects/finish.h); a
  // change pushes SetFinishCommand.
  QComboBox* finishBox() const { return finish_box_; }

 private:
  void rebuildList();
  void rebuildParameters();
  void onSpinChanged(const std::string& name);
  static constexpr int kSliderSteps = 1000;  // a slider's positions over a parameter's range

  Document* document_;
  QComboBox* add_box_;
  QListWidget* list_;
  QFormLayout* form_;
  QLabel* status_label_;
  QComboBox* finish_box_;
  std::map<std::string, std::vector<QDoubleSpinBox*>> spins_;
  int built_for_ = -1;  // the stack entry the spin boxes were made for
  std::string built_effect_;
  int gesture_ = 0;     // merge key of the running parameter edit
  std::string gesture_param_;
  int gesture_entry_ = -1;
  int gesture_stack_index_ = -1;  // the undo stack's index after the gesture's last push
  bool updating_ = false;
};

}  // namespace artcam::ui
