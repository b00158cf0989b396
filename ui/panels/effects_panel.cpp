#include "ui/panels/effects_panel.h"

#include "ui/document.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
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
  const auto it = spins_.find(name.toStdString());
  if (it == spins_.end()) return false;
  it->second->setValue(value);
  return true;
}

std::map<std::string, double> EffectsPanel::parameters() const {
  std::map<std::string, double> values;
  for (const auto& [name, spin] : spins_) values[name] = spin->value();
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
    auto* spin = new QDoubleSpinBox(this);
    spin->setDecimals(4);
    spin->setRange(p.min, p.max);
    spin->setSingleStep((p.max - p.min) / 100.0);
    spin->setValue(p.value);
    connect(spin, &QDoubleSpinBox::valueChanged, this, &EffectsPanel::schedule);
    form_->addRow(QString::fromStdString(p.name), spin);
    spins_[p.name] = spin;
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
