// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/effects_panel.h"

#include "core/pipeline/render.h"
#include "ui/document.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QTimer>
#include <QVBoxLayout>

namespace artcam::ui {

EffectsPanel::EffectsPanel(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      effect_box_(new QComboBox(this)),
      form_(new QFormLayout),
      image_label_(new QLabel(this)),
      status_label_(new QLabel(this)),
      throttle_(new QTimer(this)) {
  for (const EffectSpec& spec : effectSpecs())
    effect_box_->addItem(QString::fromStdString(spec.name));
  image_label_->setMinimumSize(160, 120);
  image_label_->setAlignment(Qt::AlignCenter);
  status_label_->setWordWrap(true);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(effect_box_);
  layout->addLayout(form_);
  layout->addWidget(image_label_, 1);
  layout->addWidget(status_label_);
  throttle_->setSingleShot(true);
  throttle_->setInterval(80);
  connect(throttle_, &QTimer::timeout, this, &EffectsPanel::startRender);
  connect(&worker_, &EffectsRenderWorker::rendered, this, &EffectsPanel::deliver);
  connect(effect_box_, &QComboBox::currentTextChanged, this, [this] {
    rebuildParameters();
    schedule();
  });
  connect(document_, &Document::photoChanged, this, &EffectsPanel::schedule);
  rebuildParameters();
  schedule();
}

// worker_ cancels its render in flight and joins: the panel goes at shutdown only.
EffectsPanel::~EffectsPanel() = default;

QString EffectsPanel::effect() const { return effect_box_->currentText(); }

void EffectsPanel::setEffect(const QString& name) { effect_box_->setCurrentText(name); }

bool EffectsPanel::setParameter(const QString& name, double value) {
  return setParameter(name, std::vector<double>{value});
}

bool EffectsPanel::setParameter(const QString& name, const std::vector<double>& value) {
  const auto it = spins_.find(name.toStdString());
  if (it == spins_.end() || it->second.size() != value.size()) return false;
  for (size_t i = 0; i < value.size(); ++i) it->second[i]->setValue(value[i]);
  return true;
}

EffectValues EffectsPanel::parameters() const {
  EffectValues values;
  for (const auto& [name, spins] : spins_)
    for (const QDoubleSpinBox* spin : spins) values[name].push_back(spin->value());
  return values;
}

void EffectsPanel::setDepth(std::shared_ptr<const ImageF> depth) {
  depth_ = std::move(depth);
  schedule();
}

QString EffectsPanel::status() const { return status_label_->text(); }

void EffectsPanel::rebuildParameters() {
  while (form_->rowCount() > 0) form_->removeRow(0);
  spins_.clear();
  const EffectSpec* spec = findEffect(effect().toStdString());
  if (!spec) return;
  for (const EffectParam& p : spec->params) {
    // A vector parameter (the haze colour) is one row of spin boxes, one per component.
    auto* row = new QHBoxLayout;
    const QString tip = QString::fromStdString(p.meaning + "; " + rangeText(p) + ", default " + defaultText(p));
    for (int i = 0; i < p.size(); ++i) {
      auto* spin = new QDoubleSpinBox(this);
      spin->setObjectName(QString::fromStdString(p.size() == 1 ? p.name : p.name + "[" + std::to_string(i) + "]"));
      spin->setDecimals(4);  // the table's ranges and defaults are multiples of 0.0001
      spin->setRange(p.min, p.max);
      spin->setSingleStep((p.max - p.min) / 100.0);
      spin->setValue(p.value[static_cast<size_t>(i)]);
      if (!p.unit.empty()) spin->setSuffix(QString::fromStdString(" " + p.unit));
      spin->setToolTip(tip);
      connect(spin, &QDoubleSpinBox::valueChanged, this, &EffectsPanel::schedule);
      row->addWidget(spin);
      spins_[p.name].push_back(spin);
    }
    form_->addRow(QString::fromStdString(p.name), row);
  }
  setToolTip(QString::fromStdString(spec->summary));
}

void EffectsPanel::schedule() {
  ++generation_;
  throttle_->start();
}

void EffectsPanel::startRender() {
  const PhotoPtr photo = document_->photo();
  if (!photo || photo->preview.empty()) return;
  // The newest request replaces any pending one and cancels the one rendering; no waiting.
  worker_.request({photo, depth_, effect().toStdString(), parameters(), generation_});
}

void EffectsPanel::deliver(quint64 generation, const QImage& image, const QString& message) {
  if (generation != generation_) return;  // stale: a newer request is on its way
  status_label_->setText(message);
  if (!image.isNull()) {
    preview_ = image;
    image_label_->setPixmap(QPixmap::fromImage(image));
  }
  shown_generation_ = generation;
  emit previewReady(generation);
}

}  // namespace artcam::ui
