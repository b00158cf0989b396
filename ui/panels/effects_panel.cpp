#include "ui/panels/effects_panel.h"

#include "core/pipeline/render.h"
#include "ui/document.h"
#include "ui/image_convert.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMetaObject>
#include <QTimer>
#include <QVBoxLayout>

#include <cmath>

namespace artcam::ui {

namespace {

constexpr int kThumbnailSide = 384;

// Far at the top, near at the bottom, log-spaced from 1 to 100: a ground plane seen level.
ImageF standInDepth(int w, int h) {
  ImageF depth(w, h, 1);
  for (int y = 0; y < h; ++y) {
    const float d = static_cast<float>(std::pow(100.0, 1.0 - (y + 0.5) / h));
    for (int x = 0; x < w; ++x) depth.pixel(x, y)[0] = d;
  }
  return depth;
}

}  // namespace

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
  connect(effect_box_, &QComboBox::currentTextChanged, this, [this] {
    rebuildParameters();
    schedule();
  });
  connect(document_, &Document::photoChanged, this, &EffectsPanel::schedule);
  rebuildParameters();
  schedule();
}

EffectsPanel::~EffectsPanel() {
  alive_->store(false);
  ++generation_;  // cancels the running render at its next band
  joinWorker();
}

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

void EffectsPanel::joinWorker() {
  if (worker_.joinable()) worker_.join();
}

void EffectsPanel::startRender() {
  const PhotoPtr photo = document_->photo();
  if (!photo || photo->preview.empty()) return;
  // One worker at a time: the previous one sees the newer generation and stops between bands.
  joinWorker();
  const quint64 generation = generation_.load();
  const ImageF source = boxDownscale(photo->preview, kThumbnailSide);
  const FrameSize frame{source.width, source.height};
  ImageF depth;
  QString depth_note;
  if (depth_ && !depth_->empty()) {
    depth = *depth_;  // any size: the renderer reads it at the same place (attributed.h)
  } else {
    depth = standInDepth(frame.width, frame.height);
    depth_note = tr("no depth painted: a ramp stands in (far at the top)");
  }
  const std::string name = effect().toStdString();
  const EffectValues values = parameters();
  std::shared_ptr<std::atomic<bool>> alive = alive_;
  worker_ = std::thread([this, alive, generation, source, depth, frame, name, values, depth_note] {
    QImage image;
    QString message;
    try {
      const Artcam camera = buildEffect(name, values, frame);
      RenderOptions options;
      options.warp.progress = [this, generation](double) { return generation_.load() == generation; };
      RenderSummary summary;
      const ImageF out = artcam::render(RenderInputs::of(source, &depth), camera, options, &summary);
      if (summary.cancelled) return;
      image = qimageFromLinear(out);
      message = QString("%1, %2 ms").arg(QString::fromStdString(summary.describe()))
                    .arg(summary.render_ms, 0, 'f', 1);
      if (findEffect(name)->needs_depth && !depth_note.isEmpty()) message += "; " + depth_note;
    } catch (const std::exception& e) {
      message = tr("cannot render: %1").arg(QString::fromUtf8(e.what()));  // caught at the boundary
    }
    if (!alive->load()) return;
    QMetaObject::invokeMethod(
        this, [this, generation, image, message] { deliver(generation, image, message); },
        Qt::QueuedConnection);
  });
}

void EffectsPanel::deliver(quint64 generation, QImage image, QString message) {
  if (generation != generation_.load()) return;  // stale: a newer request is on its way
  status_label_->setText(message);
  if (!image.isNull()) {
    preview_ = image;
    image_label_->setPixmap(QPixmap::fromImage(image));
  }
  shown_generation_ = generation;
  emit previewReady(generation);
}

}  // namespace artcam::ui
