// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/tensor_panel.h"

#include "ui/commands.h"
#include "ui/document.h"

#include <QComboBox>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <exception>
#include <optional>

namespace artcam::ui {
namespace {

// Element names inside x, e.g. "u v w" for an image position, "ar ag ab a" for colour.
QStringList elementNames(const Camera& camera) {
  QStringList names;
  for (const Block& b : camera.blocks()) {
    QStringList local;
    switch (b.kind) {
      case BlockKind::Position:
        local = b.size == 3 ? QStringList{"u", "v", "w"} : QStringList{"X", "Y", "Z", "W"};
        break;
      case BlockKind::Colour:
        local = {"ar", "ag", "ab", "a"};
        break;
      case BlockKind::Depth:
        local = {"d", "dh"};
        break;
      case BlockKind::SecondColour:
        local = {"ar2", "ag2", "ab2", "a2"};
        break;
      case BlockKind::Shading:
        local = {"s", "sh"};
        break;
    }
    while (local.size() < b.size) local << QString("x%1").arg(names.size() + local.size());
    names << local.mid(0, b.size);
  }
  return names;
}

QString blockOf(const Camera& camera, int element) {
  const BlockLayout& l = camera.layout();
  for (size_t b = 0; b < l.blocks.size(); ++b)
    if (element >= l.offsets[b] && element < l.offsets[b] + l.blocks[b].size) {
      const std::string_view n = blockKindName(l.blocks[b].kind);
      return QString::fromUtf8(n.data(), static_cast<qsizetype>(n.size()));
    }
  return {};
}

// The term entry (r, c) of Q_i weighs in output element i, for its tooltip: z_i = x Q_i xᵀ
// (eq 3), so a diagonal entry weighs x_r² and, Q_i being symmetric, an off-diagonal pair of
// entries together weighs 2·x_r·x_c.
QString termTip(const Camera& camera, const QStringList& names, int element, int r, int c,
                double value) {
  const QString term = r == c ? names.value(r) + QStringLiteral("²")
                              : QString("2·%1·%2").arg(names.value(r), names.value(c));
  const QString blocks =
      blockOf(camera, r) == blockOf(camera, c)
          ? TensorPanel::tr("%1 block").arg(blockOf(camera, r))
          : TensorPanel::tr("%1 × %2 blocks").arg(blockOf(camera, r), blockOf(camera, c));
  return TensorPanel::tr("Q%1[%2, %3]: the weight of %4 (%5) in output %6 (%7 block)\n= %8")
      .arg(element + 1)
      .arg(names.value(r), names.value(c), term, blocks, names.value(element),
           blockOf(camera, element), QString::number(value, 'g', 17));
}

// Merge keys for SetCameraCommand must not collide with other command ids (commands.h).
constexpr int kTensorEditMergeBase = 0;  // typed edits are separate undo steps: no merging

}  // namespace

TensorPanel::TensorPanel(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      stage_box_(new QComboBox(this)),
      preset_box_(new QComboBox(this)),
      tables_layout_(new QVBoxLayout),
      summary_label_(new QLabel(this)) {
  summary_label_->setWordWrap(true);
  preset_message_ = new QLabel(this);
  preset_message_->setWordWrap(true);
  preset_message_->hide();
  preset_box_->addItem(tr("Identity"), "identity");
  for (const EffectSpec& spec : effectSpecs()) {
    if (spec.needs_depth || spec.needs_second) continue;  // the photo alone cannot show them
    preset_box_->addItem(QString::fromStdString(spec.label), QString::fromStdString(spec.name));
    preset_box_->setItemData(preset_box_->count() - 1, QString::fromStdString(spec.summary),
                             Qt::ToolTipRole);
  }
  auto* apply = new QPushButton(tr("Apply preset"), this);
  auto* fitted = new QPushButton(tr("Use fitted"), this);
  fitted->setToolTip(tr("Go back to the camera fitted from the pairs"));
  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel(tr("Stage"), this));
  top->addWidget(stage_box_);
  top->addStretch(1);
  top->addWidget(preset_box_);
  top->addWidget(apply);
  top->addWidget(fitted);
  auto* content = new QWidget(this);
  content->setLayout(tables_layout_);
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setWidget(content);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addLayout(top);
  layout->addWidget(preset_message_);
  layout->addWidget(summary_label_);
  layout->addWidget(scroll, 1);

  connect(apply, &QPushButton::clicked, this,
          [this] { applyPreset(preset_box_->currentData().toString()); });
  connect(fitted, &QPushButton::clicked, this, [this] {
    if (document_->manualCamera())
      document_->undoStack()->push(
          new SetCameraCommand(document_, std::nullopt, tr("Use fitted camera")));
  });
  connect(stage_box_, &QComboBox::currentIndexChanged, this, [this](int) { refresh(); });
  connect(document_, &Document::cameraChanged, this, &TensorPanel::rebuild);
  rebuild();
}

QString TensorPanel::summary() const {
  const Artcam& whole = document_->artcam();
  QStringList blocks;
  for (const Block& b : whole.blocks()) {
    const std::string_view n = blockKindName(b.kind);
    blocks << QString::fromUtf8(n.data(), static_cast<qsizetype>(n.size()));
  }
  const std::string_view kind = artcamKindName(whole.kind());
  const int layers = static_cast<int>(whole.layers.size());
  const QString kind_text = QString::fromUtf8(kind.data(), static_cast<qsizetype>(kind.size()));
  QString text = layers == 1 ? tr("Whole camera: %1, 1 layer, blocks %2")
                                   .arg(kind_text, blocks.join(" | "))
                             : tr("Whole camera: %1, %2 layers, blocks %3")
                                   .arg(kind_text, QString::number(layers), blocks.join(" | "));
  if (whole.isPiecewise())
    text += tr(", %1 patches").arg(whole.pieces->patches.size());
  if (whole.depth_output == DepthOutput::BlurVariance) text += tr(", depth output: blur variance");
  QStringList effects;
  for (const EffectStep& e : document_->effects())
    effects << QString::fromStdString(effectLabel(e.effect));
  if (!effects.isEmpty()) text += tr("; effects: %1").arg(effects.join(" → "));
  text += tr(". The tables edit the geometry (layer 1)");
  if (document_->manualCamera()) text += tr(", set by hand");
  return text + ".";
}

void TensorPanel::rebuild() {
  summary_label_->setText(summary());
  const Camera& cam = document_->camera();
  const int n = cam.dimension();
  const int stages = static_cast<int>(cam.stages().size());
  if (n != built_dimension_ || stages != built_stages_) {
    for (QTableWidget* t : tables_) delete t->parentWidget();
    tables_.clear();
    {
      const QSignalBlocker block(stage_box_);
      stage_box_->clear();
      for (int s = 0; s < stages; ++s) stage_box_->addItem(QString::number(s + 1));
    }
    const QStringList names = elementNames(cam);
    for (int i = 0; i < n; ++i) {
      auto* box =
          new QGroupBox(tr("Q%1 → %2 (%3)").arg(i + 1).arg(names.value(i), blockOf(cam, i)), this);
      auto* table = new QTableWidget(n, n, box);
      table->setHorizontalHeaderLabels(names);
      table->setVerticalHeaderLabels(names);
      table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
      table->verticalHeader()->setDefaultSectionSize(22);
      table->setMinimumHeight(24 + 22 * n);
      table->setSizeAdjustPolicy(QAbstractScrollArea::AdjustToContents);
      auto* box_layout = new QVBoxLayout(box);
      box_layout->setContentsMargins(2, 2, 2, 2);
      box_layout->addWidget(table);
      tables_layout_->addWidget(box);
      tables_.push_back(table);
      connect(table, &QTableWidget::itemChanged, this, [this, i](QTableWidgetItem* item) {
        if (updating_) return;
        bool ok = false;
        const double v = item->text().toDouble(&ok);
        if (!ok || !std::isfinite(v)) {
          refresh();  // put the old value back
          return;
        }
        setEntry(std::max(0, stage_box_->currentIndex()), i, item->row(), item->column(), v);
      });
    }
    built_dimension_ = n;
    built_stages_ = stages;
  }
  refresh();
}

void TensorPanel::refresh() {
  const Camera& cam = document_->camera();
  const int stage = std::max(0, stage_box_->currentIndex());
  if (stage >= static_cast<int>(cam.stages().size())) return;
  updating_ = true;
  const auto& q = cam.stages()[static_cast<size_t>(stage)].q;
  const QStringList names = elementNames(cam);
  for (size_t i = 0; i < tables_.size() && i < q.size(); ++i) {
    QTableWidget* t = tables_[i];
    for (int r = 0; r < q[i].rows(); ++r)
      for (int c = 0; c < q[i].cols(); ++c) {
        const QString text = entryText(q[i](r, c));
        QTableWidgetItem* item = t->item(r, c);
        if (!item) {
          item = new QTableWidgetItem;
          item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
          t->setItem(r, c, item);
        }
        if (item->text() != text) item->setText(text);
        item->setToolTip(termTip(cam, names, static_cast<int>(i), r, c, q[i](r, c)));
      }
  }
  updating_ = false;
}

QString TensorPanel::entryText(double value) {
  // A fit's round-off (6.3e-16 where the model has no term) reads as the zero it is; the rest
  // to six significant digits, the exact value in the tooltip.
  if (std::abs(value) < kZeroBelow) return QStringLiteral("0");
  return QString::number(value, 'g', 6);
}

void TensorPanel::setEntry(int stage, int element, int row, int col, double value) {
  Camera cam = document_->camera();
  auto& stages = cam.stages();
  if (stage < 0 || stage >= static_cast<int>(stages.size())) return;
  auto& q = stages[static_cast<size_t>(stage)].q;
  if (element < 0 || element >= static_cast<int>(q.size())) return;
  Eigen::MatrixXd& m = q[static_cast<size_t>(element)];
  if (row < 0 || col < 0 || row >= m.rows() || col >= m.cols()) return;
  if (m(row, col) == value && m(col, row) == value) return;
  m(row, col) = value;
  m(col, row) = value;  // symmetric storage (eq 10)
  // Only the geometry (the first layer) is edited here; a whole camera set by hand keeps its
  // other layers, patches and depth output.
  Artcam whole = document_->manualCamera() ? *document_->manualCamera() : Artcam(cam);
  whole.main() = std::move(cam);
  document_->undoStack()->push(new SetCameraCommand(
      document_, std::move(whole),
      tr("Set Q%1(%2, %3) = %4").arg(element + 1).arg(row + 1).arg(col + 1).arg(value),
      kTensorEditMergeBase));
}

std::vector<std::pair<QString, QString>> TensorPanel::presets() const {
  std::vector<std::pair<QString, QString>> out;
  for (int i = 0; i < preset_box_->count(); ++i)
    out.emplace_back(preset_box_->itemData(i).toString(), preset_box_->itemText(i));
  return out;
}

QString TensorPanel::applyPreset(const QString& name, const EffectValues& values) {
  const FrameSize f = document_->frame();
  QString problem;
  std::optional<Artcam> camera;
  const int index = preset_box_->findData(name);
  if (!f.isImage()) {
    problem = tr("Open a photo first: a preset is made in its frame");
  } else if (index < 0) {
    problem = tr("No preset \"%1\"").arg(name);
  } else if (name == "identity") {
    camera = Artcam(Camera::identity({Block{BlockKind::Position, 3}}, f, f));
  } else {
    try {
      camera = buildEffect(name.toStdString(), values, f);  // what `artcam preset NAME` writes
    } catch (const std::exception& e) {
      problem = tr("%1 not applied: %2")
                    .arg(preset_box_->itemText(index), QString::fromUtf8(e.what()));
    }
  }
  preset_message_->setText(problem);
  preset_message_->setVisible(!problem.isEmpty());
  if (!camera) return problem;
  document_->undoStack()->push(new SetCameraCommand(
      document_, std::move(*camera), tr("Preset: %1").arg(preset_box_->itemText(index))));
  return {};
}

}  // namespace artcam::ui
