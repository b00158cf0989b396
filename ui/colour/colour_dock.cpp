// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/colour_dock.h"

#include "core/colour/colour_difference.h"
#include "core/colour/colour_map.h"
#include "core/colour/colour_stage.h"
#include "core/colour/transfer.h"
#include "core/io/matches_csv.h"
#include "ui/background_job.h"
#include "ui/colour/colour_commands.h"
#include "ui/colour/colour_fit_job.h"
#include "ui/colour/colour_project.h"
#include "ui/colour/patch_view.h"
#include "ui/document.h"
#include "ui/image_loader.h"
#include "ui/save_names.h"
#include "ui/session.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <memory>

namespace artcam::ui {
namespace {

enum Column { kNumber, kSource, kReference, kDeltaE, kDeltaEFitted, kColumns };

QColor displayColour(const Eigen::VectorXd& linear) {
  const Transfer srgb = Transfer::srgb();
  auto code = [&](double v) {
    return static_cast<int>(
        std::lround(255.0 * std::clamp(srgb.encode(std::clamp(v, 0.0, 1.0)), 0.0, 1.0)));
  };
  return QColor(code(linear[0]), code(linear[1]), code(linear[2]));
}

QString modelName(ColourModel model) {
  const std::string_view name = colourModelName(model);
  return QString::fromUtf8(name.data(), static_cast<qsizetype>(name.size()));
}

QString colourText(const Eigen::VectorXd& c) {
  return QStringLiteral("%1 %2 %3").arg(c[0], 0, 'f', 3).arg(c[1], 0, 'f', 3).arg(c[2], 0, 'f', 3);
}

}  // namespace

ColourDock::ColourDock(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      model_(new ColourSampleModel(document, this)),
      job_(new ColourFitJob(this)),
      source_view_(new PatchView(tr("Open a photo"), this)),
      reference_view_(
          new PatchView(tr("Open a reference photo: the colours the source should take"), this)),
      table_(new QTableWidget(0, kColumns, this)),
      radius_(new QSpinBox(this)),
      model_box_(new QComboBox(this)),
      robust_(new QCheckBox(tr("Robust"), this)),
      fit_button_(new QPushButton(tr("Fit colour"), this)),
      report_(new QLabel(this)) {
  auto* open = new QPushButton(tr("Reference…"), this);
  open->setToolTip(tr("Open the reference photo whose colours the source should match"));
  radius_->setRange(0, kMaxPatchRadius);
  radius_->setValue(model_->state().radius);
  radius_->setPrefix(tr("radius "));
  radius_->setSuffix(tr(" px"));
  radius_->setToolTip(
      tr("Patch half-side: the colour is the mean over (2r + 1)² pixels, in linear light"));
  const std::pair<ColourModel, QString> models[] = {
      {ColourModel::Auto, tr("Auto (model selection)")},
      {ColourModel::Linear, tr("Linear 3×3")},
      {ColourModel::Affine, tr("Affine")},
      {ColourModel::RootPolynomial, tr("Root-polynomial")},
      {ColourModel::Quadratic, tr("Rational quadratic")}};
  for (const auto& [m, label] : models) model_box_->addItem(label, static_cast<int>(m));
  robust_->setToolTip(tr("MSAC over minimal sets; samples above 3 ΔE00 count as outliers"));
  auto* clear = new QPushButton(tr("Clear colour"), this);
  clear->setToolTip(tr("Remove the colour block from the camera (undoable)"));
  auto* export_csv = new QPushButton(tr("CSV…"), this);
  export_csv->setToolTip(
      tr("Export the samples as src_r,…,dst_b (linear) for artcam fit --block colour"));
  auto* remove = new QPushButton(tr("Delete"), this);

  auto* row1 = new QHBoxLayout;
  row1->addWidget(open);
  row1->addWidget(radius_);
  row1->addWidget(model_box_, 1);
  row1->addWidget(robust_);
  auto* row2 = new QHBoxLayout;
  row2->addWidget(fit_button_);
  row2->addWidget(clear);
  row2->addWidget(export_csv);
  row2->addWidget(remove);
  row2->addStretch(1);
  auto* views = new QSplitter(Qt::Horizontal, this);
  views->addWidget(source_view_);
  views->addWidget(reference_view_);
  table_->setHorizontalHeaderLabels(
      {tr("#"), tr("Source"), tr("Reference"), tr("ΔE"), tr("ΔE fit")});
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->verticalHeader()->hide();
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  report_->setWordWrap(true);
  report_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addLayout(row1);
  auto* split = new QSplitter(Qt::Vertical, this);
  split->addWidget(views);
  split->addWidget(table_);
  layout->addWidget(split, 1);
  layout->addLayout(row2);
  layout->addWidget(report_);

  connect(open, &QPushButton::clicked, this, &ColourDock::openReferenceDialog);
  connect(radius_, &QSpinBox::valueChanged, this, &ColourDock::setRadius);
  connect(fit_button_, &QPushButton::clicked, this, &ColourDock::fit);
  connect(clear, &QPushButton::clicked, this, &ColourDock::clearColourBlock);
  connect(export_csv, &QPushButton::clicked, this, &ColourDock::exportCsvDialog);
  connect(remove, &QPushButton::clicked, this, &ColourDock::deleteSelected);
  connect(job_, &ColourFitJob::finished, this, &ColourDock::onFitted);
  for (const bool ref : {false, true}) {
    PatchView* v = ref ? reference_view_ : source_view_;
    connect(v, &PatchView::pressedEmpty, this,
            [this, ref](const Eigen::Vector2d& p) { onPressed(ref, p); });
    connect(v, &PatchView::pressedMark, this, [this, ref](int i) { onPressedMark(ref, i); });
    connect(v, &PatchView::draggedTo, this,
            [this, ref](const Eigen::Vector2d& p) { onDragged(ref, p); });
    connect(v, &PatchView::released, this, [this] { drag_index_ = -1; });
  }
  connect(table_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
    if (updating_table_ || item->column() != kNumber) return;
    const int row = item->row();
    ColourSampleState s = model_->state();
    if (row < 0 || row >= static_cast<int>(s.samples.size())) return;
    s.samples[static_cast<size_t>(row)].enabled = item->checkState() == Qt::Checked;
    pushColourSamples(model_, std::move(s), tr("Enable/disable colour sample"));
  });
  connect(table_, &QTableWidget::itemSelectionChanged, this, [this] {
    if (updating_table_) return;
    std::vector<int> rows;
    for (const QModelIndex& i : table_->selectionModel()->selectedRows()) rows.push_back(i.row());
    model_->setSelection(std::move(rows));
  });
  connect(model_, &ColourSampleModel::changed, this, [this] {
    if (radius_->value() != model_->state().radius) {
      const QSignalBlocker block(radius_);
      radius_->setValue(model_->state().radius);
    }
    refreshViews();
    refreshTable();
  });
  connect(model_, &ColourSampleModel::selectionChanged, this, [this] {
    refreshViews();
    refreshTable();
  });
  connect(document_, &Document::photoChanged, this, [this] {
    pending_source_.reset();
    last_fit_.reset();
    refreshViews();
    refreshReport();
  });
  // The full photo of a first look: sharper patches, the same samples.
  connect(document_, &Document::photoRefined, this, &ColourDock::refreshViews);
  connect(document_, &Document::cameraChanged, this, &ColourDock::refreshTable);
  refreshViews();
  refreshTable();
  refreshReport();
}

ColourDock::~ColourDock() = default;  // the loader is a child: it cancels its read, no wait

void ColourDock::attachToSession(Session* session) {
  Session::ProjectPart part;
  part.name = QStringLiteral("colour");
  part.save = [this] { return colourPartToJson(model_->state(), document_->colourBlock()); };
  part.load = [this](const QJsonObject& json) {
    auto loaded = colourPartFromJson(json, "project: /parts/colour");
    if (!loaded) {
      message_ = QString::fromStdString(loaded.status.message);
      refreshReport();
      emit statusMessage(message_);
      return;
    }
    // Part of opening, not undoable edits.
    const QString reference = loaded->state.reference_path;
    model_->setState(std::move(loaded->state));
    if (loaded->colour_block) document_->setColourBlock(std::move(loaded->colour_block));
    if (!reference.isEmpty()) startReferenceLoad(reference, /*undoable=*/false);
    if (!model_->state().samples.empty()) emit samplesRestored();
  };
  session->addProjectPart(std::move(part));
}

ColourFitOptions ColourDock::fitOptions() const {
  ColourFitOptions o;
  o.model = static_cast<ColourModel>(model_box_->currentData().toInt());
  o.robust = robust_->isChecked();
  return o;
}

void ColourDock::setFitModel(ColourModel model) {
  model_box_->setCurrentIndex(model_box_->findData(static_cast<int>(model)));
}

void ColourDock::setRobust(bool robust) { robust_->setChecked(robust); }

bool ColourDock::isFitting() const { return job_->isRunning(); }

void ColourDock::openReferenceDialog() {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open Reference Photo"), {},
      tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.hdr);;All files (*)"));
  if (!path.isEmpty()) openReference(path);
}

void ColourDock::openReference(const QString& path) { startReferenceLoad(path, true); }

void ColourDock::startReferenceLoad(const QString& path, bool undoable) {
  if (loader_) {
    loader_->cancel();
    loader_->disconnect(this);
  }
  auto* loader = new ImageLoader(QFileInfo(path).absoluteFilePath(), this);
  loader_ = loader;
  loader_undoable_ = undoable;
  connect(loader, &ImageLoader::loaded, this, [this, loader](const PhotoPtr& photo) {
    if (loader != loader_) return;
    ColourSampleState s = model_->state();
    s.reference = photo;
    s.reference_path = photo->path;
    pending_reference_.reset();
    if (loader_undoable_)
      pushColourSamples(model_, std::move(s), tr("Open reference photo"));
    else
      model_->setState(std::move(s));
    message_.clear();
    refreshReport();
    emit referenceLoaded(true, photo->path);
  });
  connect(loader, &ImageLoader::failed, this, [this, loader](const QString& message) {
    if (loader != loader_) return;
    message_ = tr("Reference photo: %1").arg(message);
    refreshReport();
    emit statusMessage(message_);
    emit referenceLoaded(false, message);
  });
  connect(loader, &ImageLoader::finished, loader, &QObject::deleteLater);
  loader->start();
}

void ColourDock::setRadius(int radius) {
  ColourSampleState s = model_->state();
  s.radius = std::clamp(radius, 0, kMaxPatchRadius);
  // Spin-box steps in a row are one undo step (a gesture id per spin box focus is overkill).
  pushColourSamples(model_, std::move(s), tr("Patch radius %1 px").arg(radius), /*gesture=*/-1);
}

void ColourDock::onPressed(bool reference_side, const Eigen::Vector2d& px) {
  drag_index_ = -1;
  (reference_side ? pending_reference_ : pending_source_) = px;
  if (pending_source_ && pending_reference_) {
    ColourSampleState s = model_->state();
    s.samples.push_back({*pending_source_, *pending_reference_, true});
    pending_source_.reset();
    pending_reference_.reset();
    const int index = static_cast<int>(s.samples.size()) - 1;
    pushColourSamples(model_, std::move(s), tr("Add colour sample"));
    model_->setSelection({index});
  }
  refreshViews();
}

void ColourDock::onPressedMark(bool reference_side, int index) {
  model_->setSelection({index});
  drag_index_ = index;
  drag_reference_ = reference_side;
  gesture_ = gesture_ % 1000000 + 1;  // positive: one merge id per drag
}

void ColourDock::onDragged(bool reference_side, const Eigen::Vector2d& px) {
  if (drag_index_ < 0 || reference_side != drag_reference_) return;
  ColourSampleState s = model_->state();
  if (drag_index_ >= static_cast<int>(s.samples.size())) return;
  ColourSample& sample = s.samples[static_cast<size_t>(drag_index_)];
  (reference_side ? sample.reference : sample.source) = px;
  pushColourSamples(model_, std::move(s), tr("Move colour sample"), gesture_);
}

void ColourDock::deleteSelected() {
  const std::vector<int>& sel = model_->selection();
  if (sel.empty()) return;
  ColourSampleState s = model_->state();
  for (auto it = sel.rbegin(); it != sel.rend(); ++it)
    if (*it < static_cast<int>(s.samples.size())) s.samples.erase(s.samples.begin() + *it);
  model_->setSelection({});
  pushColourSamples(model_, std::move(s),
                    sel.size() == 1 ? tr("Delete colour sample") : tr("Delete colour samples"));
}

void ColourDock::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) {
    deleteSelected();
  } else if (event->key() == Qt::Key_Escape) {
    pending_source_.reset();
    pending_reference_.reset();
    refreshViews();
  } else {
    QWidget::keyPressEvent(event);
  }
}

void ColourDock::fit() {
  if (!document_->photo()) return;
  // The check fitColourSamples makes, before the job starts: the options the CLI refuses are
  // refused here with the same reason.
  const ColourFitOptions options = fitOptions();
  if (const Status s = options.check(); !s) {
    message_ = QString::fromStdString(s.message);
    refreshReport();
    return;
  }
  message_ = tr("Fitting…");
  refreshReport();
  const FrameSize f = document_->frame();
  job_->start(model_->colourPairs(), options,
              (static_cast<quint64>(f.width) << 32) | static_cast<quint64>(f.height));
}

void ColourDock::onFitted(const ColourFitSummary& summary, quint64 tag) {
  last_fit_ = summary;
  message_.clear();
  const FrameSize f = document_->frame();
  const quint64 frame_tag = (static_cast<quint64>(f.width) << 32) | static_cast<quint64>(f.height);
  bool ok = summary.status.ok && summary.stored && tag == frame_tag && f.isImage();
  if (summary.status.ok && !summary.stored)
    message_ =
        tr("Root-polynomial is not a quadratic form: an ARTcam cannot hold it, so the "
           "camera's colour is unchanged (Auto picks the best storable model).");
  if (ok) {
    try {
      document_->undoStack()->push(
          new SetColourBlockCommand(document_, colourCamera(summary.map, f),
                                    tr("Fit colour (%1)").arg(modelName(summary.map.model))));
    } catch (const std::exception& e) {
      message_ = tr("Colour fit: %1").arg(QString::fromUtf8(e.what()));
      ok = false;
    }
  }
  refreshReport();
  emit fitFinished(ok);
}

void ColourDock::clearColourBlock() {
  if (document_->colourBlock())
    document_->undoStack()->push(
        new SetColourBlockCommand(document_, std::nullopt, tr("Clear colour")));
}

bool ColourDock::exportCsv(const QString& path) {
  // The pairs are taken here (the samples live on this thread), written on a job's.
  auto pairs = std::make_shared<const std::vector<PointMatch>>(model_->colourPairs());
  runInBackground(
      this,
      [path, pairs](JobContext&) { return writeColourSamplesCsv(path.toStdString(), *pairs); },
      [this, path, count = pairs->size()](JobOutcome<Status> outcome) {
        const bool ok = outcome.value && outcome.value->ok;
        message_ = ok              ? tr("Exported %1 colour samples to %2").arg(count).arg(path)
                   : outcome.value ? QString::fromStdString(outcome.value->message)
                                   : tr("%1: %2").arg(path, outcome.error);
        refreshReport();
        emit statusMessage(message_);
        emit csvExported(ok, message_);
      });
  return true;
}

void ColourDock::exportCsvDialog() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export Colour Samples"),
      proposedSavePath(document_->photo() ? document_->photo()->path : QString(), "_colour.csv"),
      tr("CSV (*.csv)"));
  if (!path.isEmpty()) exportCsv(path);
}

void ColourDock::refreshViews() {
  const PhotoPtr& photo = document_->photo();
  source_view_->setPhoto(photo ? photo->display : QImage(), photo ? photo->size() : FrameSize{});
  const PhotoPtr& ref = model_->state().reference;
  reference_view_->setPhoto(ref ? ref->display : QImage(), ref ? ref->size() : FrameSize{});
  std::vector<PatchMark> source_marks, reference_marks;
  const auto& samples = model_->state().samples;
  for (size_t i = 0; i < samples.size(); ++i) {
    const bool selected = std::binary_search(model_->selection().begin(), model_->selection().end(),
                                             static_cast<int>(i));
    source_marks.push_back(
        {samples[i].source, static_cast<int>(i) + 1, selected, samples[i].enabled, false});
    reference_marks.push_back(
        {samples[i].reference, static_cast<int>(i) + 1, selected, samples[i].enabled, false});
  }
  if (pending_source_) source_marks.push_back({*pending_source_, 0, false, true, true});
  if (pending_reference_) reference_marks.push_back({*pending_reference_, 0, false, true, true});
  source_view_->setMarks(std::move(source_marks), model_->state().radius);
  reference_view_->setMarks(std::move(reference_marks), model_->state().radius);
}

void ColourDock::refreshTable() {
  updating_table_ = true;
  const auto& samples = model_->state().samples;
  table_->setRowCount(static_cast<int>(samples.size()));
  const std::optional<Camera>& block = document_->colourBlock();
  for (int row = 0; row < static_cast<int>(samples.size()); ++row) {
    auto cell = [&](int col) {
      QTableWidgetItem* item = table_->item(row, col);
      if (!item) {
        item = new QTableWidgetItem;
        table_->setItem(row, col, item);
      }
      return item;
    };
    QTableWidgetItem* number = cell(kNumber);
    number->setText(QString::number(row + 1));
    number->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsUserCheckable);
    number->setCheckState(samples[static_cast<size_t>(row)].enabled ? Qt::Checked : Qt::Unchecked);
    const std::optional<PointMatch> pair = model_->colourPair(row);
    for (int col = kSource; col < kColumns; ++col) cell(col)->setText(QStringLiteral("–"));
    cell(kSource)->setBackground(QBrush());
    cell(kReference)->setBackground(QBrush());
    if (!pair) continue;
    cell(kSource)->setText(colourText(pair->source));
    cell(kSource)->setBackground(displayColour(pair->source));
    cell(kSource)->setForeground(pair->source.mean() > 0.18 ? Qt::black : Qt::white);
    cell(kReference)->setText(colourText(pair->target));
    cell(kReference)->setBackground(displayColour(pair->target));
    cell(kReference)->setForeground(pair->target.mean() > 0.18 ? Qt::black : Qt::white);
    cell(kDeltaE)->setText(QString::number(deltaE2000(pair->source, pair->target), 'f', 2));
    double mapped[3];
    const double src[3] = {pair->source[0], pair->source[1], pair->source[2]};
    if (block && applyColourCamera(*block, src, mapped))
      cell(kDeltaEFitted)
          ->setText(QString::number(
              deltaE2000(Eigen::Vector3d(mapped[0], mapped[1], mapped[2]), pair->target), 'f', 2));
  }
  table_->clearSelection();
  for (int i : model_->selection()) table_->selectRow(i);
  updating_table_ = false;
}

QString ColourDock::report() const {
  QString text;
  if (last_fit_) {
    const ColourFitSummary& s = *last_fit_;
    if (s.status.ok) {
      text = tr("%1 — chosen: %2. %3")
                 .arg(QString::fromStdString(s.report()), modelName(s.selected),
                      QString::fromStdString(s.reason));
      // The selection's evidence: every candidate's held-out ΔE00 (– where not computable).
      QStringList held_out;
      for (const ColourCandidate& c : s.candidates)
        held_out << tr("%1 %2").arg(modelName(c.model), c.fitted && c.held_out_de >= 0.0
                                                            ? QString::number(c.held_out_de, 'f', 2)
                                                            : QStringLiteral("–"));
      if (!held_out.isEmpty()) text += tr("\nHeld-out ΔE00: %1").arg(held_out.join(", "));
    } else
      text = QString::fromStdString(s.status.message);
  }
  if (!message_.isEmpty()) text = text.isEmpty() ? message_ : message_ + "\n" + text;
  if (text.isEmpty())
    text = tr("Click a patch on the source, then the matching patch on the reference.");
  return text;
}

void ColourDock::refreshReport() { report_->setText(report()); }

}  // namespace artcam::ui
