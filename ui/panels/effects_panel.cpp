// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/effects_panel.h"

#include "ui/commands.h"
#include "ui/document.h"

#include "core/effects/finish.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>

#include <cmath>

namespace artcam::ui {
namespace {

// The table's human name ("General linear view" for photo-glc).
QString humanName(const std::string& name) { return QString::fromStdString(effectLabel(name)); }

}  // namespace

EffectsPanel::EffectsPanel(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      add_box_(new QComboBox(this)),
      list_(new QListWidget(this)),
      form_(new QFormLayout),
      status_label_(new QLabel(this)),
      finish_box_(new QComboBox(this)) {
  // Marks after the render (G'MIC, core/effects/finish.h): not a camera, so not in the stack,
  // but part of the picture the preview, the export and the project show.
  finish_box_->addItem(tr("None"), QString());
  for (const FinishInfo& f : finishes()) {
    finish_box_->addItem(QString::fromStdString(f.name), QString::fromStdString(f.name));
    finish_box_->setItemData(finish_box_->count() - 1, QString::fromStdString(f.description),
                             Qt::ToolTipRole);
  }
  finish_box_->setToolTip(
      tr("Marks drawn over the result (pencil, charcoal, painting, cartoon), "
         "as artcam warp --finish draws them"));
  for (const EffectSpec& spec : effectSpecs()) {
    add_box_->addItem(QString::fromStdString(spec.label), QString::fromStdString(spec.name));
    add_box_->setItemData(add_box_->count() - 1, QString::fromStdString(spec.summary),
                          Qt::ToolTipRole);
  }
  auto* add = new QPushButton(tr("&Add"), this);  // Alt+A: pick in the list, add by keyboard
  add->setToolTip(tr("Add the effect to the end of the stack (applied after the others)"));
  auto* remove = new QPushButton(tr("Remove"), this);
  auto* up = new QPushButton(tr("Up"), this);
  auto* down = new QPushButton(tr("Down"), this);
  auto* add_row = new QHBoxLayout;
  add_row->addWidget(add_box_, 1);
  add_row->addWidget(add);
  auto* edit_row = new QHBoxLayout;
  edit_row->addWidget(remove);
  edit_row->addWidget(up);
  edit_row->addWidget(down);
  list_->setMaximumHeight(120);
  list_->setToolTip(tr("The effect stack, applied top to bottom after the geometry and colour"));
  status_label_->setWordWrap(true);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(add_row);
  layout->addWidget(list_);
  layout->addLayout(edit_row);
  layout->addLayout(form_);
  layout->addWidget(status_label_);
  auto* finish_row = new QFormLayout;
  finish_row->addRow(tr("&Finish"), finish_box_);
  layout->addLayout(finish_row);
  layout->addStretch(1);
  connect(finish_box_, &QComboBox::currentIndexChanged, this, [this] {
    const std::string name = finish_box_->currentData().toString().toStdString();
    if (!updating_ && name != document_->finish())
      document_->undoStack()->push(new SetFinishCommand(document_, name));
  });
  const auto show_finish = [this] {
    const int at = finish_box_->findData(QString::fromStdString(document_->finish()));
    const bool was = updating_;
    updating_ = true;
    finish_box_->setCurrentIndex(std::max(0, at));
    updating_ = was;
  };
  connect(document_, &Document::finishChanged, this, show_finish);
  connect(document_, &Document::photoChanged, this, show_finish);
  connect(add, &QPushButton::clicked, this,
          [this] { addEffect(add_box_->currentData().toString()); });
  connect(remove, &QPushButton::clicked, this, &EffectsPanel::removeSelected);
  connect(up, &QPushButton::clicked, this, [this] { moveSelected(-1); });
  connect(down, &QPushButton::clicked, this, [this] { moveSelected(+1); });
  connect(list_, &QListWidget::currentRowChanged, this, [this] {
    if (!updating_) rebuildParameters();
  });
  connect(document_, &Document::effectsChanged, this, &EffectsPanel::rebuildList);
  // The status follows the camera: an effect reading depth joins when depth appears.
  connect(document_, &Document::cameraChanged, this, [this] { status_label_->setText(status()); });
  rebuildList();
}

EffectsPanel::~EffectsPanel() = default;

bool EffectsPanel::addEffect(const QString& name) {
  const EffectSpec* spec = findEffect(name.toStdString());
  if (!spec) return false;
  EffectStep step{spec->name, {}};
  for (const EffectParam& p : spec->params) step.values[p.name] = p.value;
  std::vector<EffectStep> effects = document_->effects();
  // A project holds at most kMaxProjectEffects (studio_project.h): a longer stack would be
  // saved into a file no reader opens.
  if (effects.size() >= kMaxProjectEffects) {
    status_label_->setText(tr("The stack holds at most %1 effects").arg(kMaxProjectEffects));
    return false;
  }
  effects.push_back(std::move(step));
  const int index = static_cast<int>(effects.size()) - 1;
  document_->undoStack()->push(new SetEffectsCommand(
      document_, std::move(effects), tr("Add effect %1").arg(humanName(spec->name))));
  setSelectedIndex(index);
  return true;
}

void EffectsPanel::removeSelected() {
  const int i = selectedIndex();
  if (i < 0) return;
  std::vector<EffectStep> effects = document_->effects();
  const QString name = humanName(effects[static_cast<size_t>(i)].effect);
  effects.erase(effects.begin() + i);
  document_->undoStack()->push(
      new SetEffectsCommand(document_, std::move(effects), tr("Remove effect %1").arg(name)));
  setSelectedIndex(std::min(i, static_cast<int>(document_->effects().size()) - 1));
}

void EffectsPanel::moveSelected(int delta) {
  const int i = selectedIndex();
  const int j = i + delta;
  std::vector<EffectStep> effects = document_->effects();
  if (i < 0 || j < 0 || j >= static_cast<int>(effects.size())) return;
  std::swap(effects[static_cast<size_t>(i)], effects[static_cast<size_t>(j)]);
  document_->undoStack()->push(new SetEffectsCommand(
      document_, std::move(effects),
      tr("Move effect %1").arg(humanName(effects[static_cast<size_t>(j)].effect))));
  setSelectedIndex(j);
}

int EffectsPanel::selectedIndex() const {
  const int row = list_->currentRow();
  return row >= 0 && row < static_cast<int>(document_->effects().size()) ? row : -1;
}

void EffectsPanel::setSelectedIndex(int index) { list_->setCurrentRow(index); }

EffectValues EffectsPanel::parameters() const {
  EffectValues values;
  for (const auto& [name, spins] : spins_)
    for (const QDoubleSpinBox* spin : spins) values[name].push_back(spin->value());
  return values;
}

bool EffectsPanel::setParameter(const QString& name, double value) {
  return setParameter(name, std::vector<double>{value});
}

bool EffectsPanel::setParameter(const QString& name, const std::vector<double>& value) {
  const auto it = spins_.find(name.toStdString());
  if (it == spins_.end() || it->second.size() != value.size()) return false;
  for (size_t i = 0; i < value.size(); ++i) it->second[i]->setValue(value[i]);
  return true;
}

QString EffectsPanel::status() const {
  const auto& effects = document_->effects();
  if (effects.empty()) return tr("No effects. Pick one and press Add.");
  const std::string& note = document_->artcamNote();
  if (note.empty())
    return effects.size() == 1 ? tr("1 effect applied to the result.")
                               : tr("%1 effects applied to the result.").arg(effects.size());
  return QString::fromStdString(note);
}

void EffectsPanel::rebuildList() {
  const int keep = list_->currentRow();
  updating_ = true;
  list_->clear();
  const auto& effects = document_->effects();
  for (size_t i = 0; i < effects.size(); ++i)
    list_->addItem(QString("%1. %2").arg(i + 1).arg(humanName(effects[i].effect)));
  list_->setCurrentRow(std::min(keep < 0 ? 0 : keep, static_cast<int>(effects.size()) - 1));
  updating_ = false;
  rebuildParameters();
  status_label_->setText(status());
}

void EffectsPanel::rebuildParameters() {
  const int index = selectedIndex();
  const EffectStep* step =
      index >= 0 ? &document_->effects()[static_cast<size_t>(index)] : nullptr;
  // Same entry and effect: only the values change (an undo, or this panel's own edit), so the
  // spin boxes stay and keep their focus.
  if (step && index == built_for_ && step->effect == built_effect_) {
    updating_ = true;
    for (const auto& [name, spins] : spins_) {
      const auto it = step->values.find(name);
      if (it == step->values.end()) continue;
      for (size_t i = 0; i < spins.size() && i < it->second.size(); ++i)
        if (spins[i]->value() != it->second[i]) spins[i]->setValue(it->second[i]);
    }
    updating_ = false;
    return;
  }
  while (form_->rowCount() > 0) form_->removeRow(0);
  spins_.clear();
  built_for_ = index;
  built_effect_ = step ? step->effect : std::string();
  const EffectSpec* spec = step ? findEffect(step->effect) : nullptr;
  if (!spec) return;
  updating_ = true;
  for (const EffectParam& p : spec->params) {
    // A vector parameter (the haze colour) is one row of spin boxes, one per component.
    auto* row = new QHBoxLayout;
    const QString tip = QString::fromStdString(p.meaning + "; " + rangeText(p) + ", default " +
                                               defaultText(p));
    const auto given = step->values.find(p.name);
    for (int i = 0; i < p.size(); ++i) {
      auto* spin = new QDoubleSpinBox(this);
      spin->setObjectName(QString::fromStdString(
          p.size() == 1 ? p.name : p.name + "[" + std::to_string(i) + "]"));
      // The table's ranges and defaults are multiples of 0.0001; a named choice is its index.
      spin->setDecimals(p.isChoice() ? 0 : 4);
      spin->setRange(p.min, p.max);
      spin->setSingleStep(p.isChoice() ? 1.0 : (p.max - p.min) / 100.0);
      const bool has = given != step->values.end() && given->second.size() == p.value.size();
      spin->setValue(has ? given->second[static_cast<size_t>(i)] : p.value[static_cast<size_t>(i)]);
      if (!p.unit.empty()) spin->setSuffix(QString::fromStdString(" " + p.unit));
      spin->setToolTip(tip);
      const std::string name = p.name;
      connect(spin, &QDoubleSpinBox::valueChanged, this, [this, name] { onSpinChanged(name); });
      spins_[p.name].push_back(spin);
      if (!p.isChoice()) {
        // A slider beside the box for a strength to be felt rather than typed (a lens's k1):
        // it types into the spin box, so its drag is the box's one merged undo step.
        auto* slider = new QSlider(Qt::Horizontal, this);
        slider->setObjectName(spin->objectName() + "/slider");
        slider->setRange(0, kSliderSteps);
        slider->setToolTip(tip);
        const auto at = [spin] {
          return static_cast<int>(std::lround((spin->value() - spin->minimum()) /
                                              (spin->maximum() - spin->minimum()) * kSliderSteps));
        };
        slider->setValue(at());
        connect(slider, &QSlider::valueChanged, spin, [spin](int v) {
          spin->setValue(spin->minimum() + (spin->maximum() - spin->minimum()) * v / kSliderSteps);
        });
        connect(spin, &QDoubleSpinBox::valueChanged, slider, [slider, at] {
          const QSignalBlocker block(slider);
          slider->setValue(at());
        });
        row->addWidget(slider, 1);
      }
      row->addWidget(spin);
    }
    form_->addRow(QString::fromStdString(p.name), row);
  }
  updating_ = false;
  setToolTip(QString::fromStdString(spec->summary));
}

void EffectsPanel::onSpinChanged(const std::string& name) {
  if (updating_) return;
  const int index = selectedIndex();
  if (index < 0) return;
  std::vector<EffectStep> effects = document_->effects();
  EffectStep& step = effects[static_cast<size_t>(index)];
  std::vector<double> value;
  for (const QDoubleSpinBox* spin : spins_.at(name)) value.push_back(spin->value());
  if (step.values[name] == value) return;
  step.values[name] = std::move(value);
  // Edits of one parameter of one entry in a row are one undo step (a spin-box drag).
  QUndoStack* stack = document_->undoStack();
  if (name != gesture_param_ || index != gesture_entry_ || stack->index() != gesture_stack_index_)
    ++gesture_;
  gesture_param_ = name;
  gesture_entry_ = index;
  stack->push(new SetEffectsCommand(
      document_, std::move(effects),
      tr("Set %1 %2").arg(humanName(step.effect), QString::fromStdString(name)), gesture_));
  gesture_stack_index_ = stack->index();
}

}  // namespace artcam::ui
