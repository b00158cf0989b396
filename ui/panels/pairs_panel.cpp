// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/pairs_panel.h"

#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_explanation.h"
#include "ui/line_commands.h"

#include <QButtonGroup>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QTableView>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

namespace artcam::ui {
namespace {

// The Radial button's id in the model group, beside the ModelClass values.
constexpr int kRadialId = 100;

}  // namespace

PairsTableModel::PairsTableModel(Document* document, QObject* parent)
    : QAbstractTableModel(parent), document_(document) {
  connect(document_, &Document::pairCountChanged, this, [this] {
    beginResetModel();
    endResetModel();
  });
  connect(document_, &Document::pairsChanged, this, [this] {
    if (rowCount() > 0) emit dataChanged(index(0, 0), index(rowCount() - 1, ColumnCount - 1));
  });
}

int PairsTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(document_->pairs().size());
}

int PairsTableModel::columnCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : ColumnCount;
}

QVariant PairsTableModel::data(const QModelIndex& index, int role) const {
  if (!index.isValid() || index.row() >= rowCount()) return {};
  const Pair& p = document_->pairs()[static_cast<size_t>(index.row())];
  const int c = index.column();
  if (c == Enabled && role == Qt::CheckStateRole) return p.enabled ? Qt::Checked : Qt::Unchecked;
  if (role == Qt::TextAlignmentRole && c != Enabled)
    return QVariant::fromValue(Qt::AlignRight | Qt::AlignVCenter);
  const double values[] = {0.0, p.source.x(), p.source.y(), p.target.x(), p.target.y()};
  if (role == Qt::EditRole && c >= SourceX && c <= TargetY) return values[c];
  if (role != Qt::DisplayRole) return {};
  if (c >= SourceX && c <= TargetY) return QString::number(values[c], 'f', 2);
  if (c == Residual) {
    const double r = document_->residual(index.row());
    if (r < 0.0) return QString();
    return std::isfinite(r) ? QString::number(r, 'f', 2) : tr("unmapped");
  }
  return {};
}

QVariant PairsTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (role != Qt::DisplayRole) return {};
  if (orientation == Qt::Vertical) return section + 1;
  switch (section) {
    case Enabled:
      return tr("On");
    case SourceX:
      return tr("Source x");
    case SourceY:
      return tr("Source y");
    case TargetX:
      return tr("Target x");
    case TargetY:
      return tr("Target y");
    case Residual:
      return tr("Residual px");
    default:
      return {};
  }
}

Qt::ItemFlags PairsTableModel::flags(const QModelIndex& index) const {
  Qt::ItemFlags f = QAbstractTableModel::flags(index);
  if (index.column() == Enabled)
    f |= Qt::ItemIsUserCheckable;
  else if (index.column() != Residual)
    f |= Qt::ItemIsEditable;
  return f;
}

bool PairsTableModel::setData(const QModelIndex& index, const QVariant& value, int role) {
  if (!index.isValid() || index.row() >= rowCount()) return false;
  const int row = index.row();
  const Pair before = document_->pairs()[static_cast<size_t>(row)];
  if (index.column() == Enabled && role == Qt::CheckStateRole) {
    const bool on = value.toInt() == Qt::Checked;
    if (on == before.enabled) return false;
    pushTogglePairsEnabled(document_, {row});
    return true;
  }
  if (role != Qt::EditRole) return false;
  bool ok = false;
  const double v = value.toDouble(&ok);
  if (!ok || !std::isfinite(v)) return false;
  Pair after = before;
  switch (index.column()) {
    case SourceX:
      after.source.x() = v;
      break;
    case SourceY:
      after.source.y() = v;
      break;
    case TargetX:
      after.target.x() = v;
      break;
    case TargetY:
      after.target.y() = v;
      break;
    default:
      return false;
  }
  if (after == before) return false;
  document_->undoStack()->push(new MovePairsCommand(document_, {row}, {before}, {after}, 0,
                                                    tr("Edit pair %1").arg(row + 1)));
  return true;
}

PairsPanel::PairsPanel(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      model_(new PairsTableModel(document, this)),
      table_(new QTableView(this)),
      banner_(new QLabel(this)),
      models_(new QButtonGroup(this)),
      scores_(new QLabel(this)),
      reason_(new QLabel(this)),
      explanation_timer_(new QTimer(this)) {
  explanation_timer_->setSingleShot(true);
  explanation_timer_->setInterval(kExplanationMs);
  connect(explanation_timer_, &QTimer::timeout, this, &PairsPanel::updateExplanation);
  table_->setModel(model_);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  // Sized from the visible rows only: every pair edit (each mouse move of a drag) re-measures
  // the columns, which over all of 300 rows took milliseconds of the GUI thread per move.
  table_->horizontalHeader()->setResizeContentsPrecision(0);
  table_->verticalHeader()->setDefaultSectionSize(22);
  banner_->setWordWrap(true);
  auto* remove = new QPushButton(tr("Delete"), this);
  remove->setToolTip(tr("Delete the selected pairs (Del)"));
  auto* toggle = new QPushButton(tr("Enable/disable"), this);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(remove);
  buttons->addWidget(toggle);
  buttons->addStretch(1);
  // One click per model, ids are ModelClass values; the change is the Model menu's undo step.
  auto* selector = new QHBoxLayout;
  selector->setSpacing(1);
  const std::pair<ModelClass, QString> choices[] = {
      {ModelClass::Auto, tr("Auto")},          {ModelClass::Translation, tr("Transl.")},
      {ModelClass::Similarity, tr("Simil.")},  {ModelClass::Affine, tr("Affine")},
      {ModelClass::Homography, tr("Homog.")},  {ModelClass::Quadratic, tr("Quadr.")}};
  for (const auto& [m, label] : choices) {
    auto* b = new QToolButton(this);
    b->setText(label);
    b->setCheckable(true);
    b->setToolTip(m == ModelClass::Auto
                      ? tr("Auto: the simplest model the pairs support (the reason is below)")
                      : tr("Fit the %1 model").arg(QString::fromUtf8(modelClassName(m).data(),
                                                     static_cast<qsizetype>(modelClassName(m).size()))));
    models_->addButton(b, static_cast<int>(m));
    selector->addWidget(b);
    if (m == ModelClass::Auto) {
      auto* radial = new QToolButton(this);
      radial->setText(tr("Radial"));
      radial->setCheckable(true);
      models_->addButton(radial, kRadialId);
      selector->addWidget(radial);
    }
  }
  selector->addStretch(1);
  models_->setExclusive(true);
  scores_->setTextFormat(Qt::RichText);
  // Wrapped like the reason: a model's note (a pole's position, say) is one long table cell, and
  // unwrapped it widened the dock mid-session, shrinking the canvas under the user's clicks.
  scores_->setWordWrap(true);
  reason_->setWordWrap(true);
  reason_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  QFont small = reason_->font();
  small.setPointSizeF(small.pointSizeF() * 0.9);
  reason_->setFont(small);
  scores_->setFont(small);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(banner_);
  layout->addWidget(table_, 1);
  layout->addLayout(buttons);
  layout->addLayout(selector);
  // The explanation lives in a box of fixed height: its text changes length with every fit, and
  // laid out directly it pushed the model buttons up and down a line whenever it rewrapped.
  auto* explanation = new QWidget;
  auto* explanation_layout = new QVBoxLayout(explanation);
  explanation_layout->setContentsMargins(0, 0, 0, 0);
  explanation_layout->addWidget(scores_);
  explanation_layout->addWidget(reason_);
  explanation_layout->addStretch(1);
  auto* explanation_box = new QScrollArea(this);
  explanation_box->setObjectName("fitExplanation");
  explanation_box->setWidget(explanation);
  explanation_box->setWidgetResizable(true);
  explanation_box->setFrameShape(QFrame::NoFrame);
  explanation_box->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  explanation_box->setFixedHeight(QFontMetrics(small).lineSpacing() * kExplanationLines);
  layout->addWidget(explanation_box);

  connect(models_, &QButtonGroup::idClicked, this, &PairsPanel::chooseModel);
  connect(document_, &Document::modelChanged, this, &PairsPanel::updateExplanation);
  connect(document_, &Document::linesChanged, this, &PairsPanel::updateModelButtons);
  connect(document_, &Document::cameraChanged, this, &PairsPanel::scheduleExplanation);

  connect(remove, &QPushButton::clicked, this, [this] { pushDeleteSelection(document_); });
  connect(toggle, &QPushButton::clicked, this,
          [this] { pushTogglePairsEnabled(document_, document_->selection()); });
  connect(document_, &Document::cameraChanged, this, &PairsPanel::updateBanner);
  connect(document_, &Document::selectionChanged, this, &PairsPanel::selectionFromDocument);
  connect(document_, &Document::pairCountChanged, this, &PairsPanel::selectionFromDocument);
  connect(table_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
          &PairsPanel::selectionToDocument);
  updateBanner();
  updateExplanation();
}

QString PairsPanel::bannerText() const { return banner_->text(); }
QAbstractButton* PairsPanel::radialButton() const { return models_->button(kRadialId); }

void PairsPanel::chooseModel(int id) {
  if (!document_->linesDriveFit()) {
    if (id == kRadialId) return;  // disabled; a programmatic click changes nothing
    const auto chosen = static_cast<ModelClass>(id);
    if (document_->model() != chosen)
      document_->undoStack()->push(new SetModelCommand(document_, chosen));
    return;
  }
  // Lines drive the fit: Auto, Radial and Quadr. name the line fit's model.
  ModelClass model = document_->model();
  LineModel line_model = LineModel::Auto;
  QString text;
  if (id == kRadialId) {
    line_model = LineModel::Radial;
    if (model == ModelClass::Quadratic) model = ModelClass::Auto;
    text = tr("Lines model: radial");
  } else if (id == static_cast<int>(ModelClass::Quadratic)) {
    model = ModelClass::Quadratic;
    text = tr("Lines model: quadratic");
  } else if (id == static_cast<int>(ModelClass::Auto)) {
    model = ModelClass::Auto;
    text = tr("Lines model: auto");
  } else {
    return;  // disabled while lines drive the fit
  }
  if (model != document_->model() || line_model != document_->lineModel())
    document_->undoStack()->push(new SetModelChoiceCommand(document_, model, line_model, text));
  else
    updateModelButtons();  // a click on the checked button: keep it checked
}

void PairsPanel::updateModelButtons() {
  const bool lines = document_->linesDriveFit();
  for (QAbstractButton* b : models_->buttons()) {
    const int id = models_->id(b);
    const bool for_lines = id == kRadialId || id == static_cast<int>(ModelClass::Auto) ||
                           id == static_cast<int>(ModelClass::Quadratic);
    const bool applies = lines ? for_lines : id != kRadialId;
    b->setEnabled(applies);
    QString tip;
    if (id == kRadialId)
      tip = applies ? tr("Radial: one lens coefficient about the frame centre; straightens the "
                         "lines without changing their spacing")
                    : tr("Radial is a lens for straight lines: trace lines with the Line tool");
    else if (!applies)
      tip =
          tr("Lines drive the fit: they determine a lens (Auto, Radial or Quadr.), not this "
             "model; it applies to pairs alone");
    else if (lines && id == static_cast<int>(ModelClass::Auto))
      tip =
          tr("Auto for lines: the radial lens, or the quadratic only when held-out lines "
             "confirm it and it adds no keystone or empty frame");
    else if (id == static_cast<int>(ModelClass::Auto))
      tip = tr("Auto: the simplest model the pairs support (the reason is below)");
    else {
      const std::string_view name = modelClassName(static_cast<ModelClass>(id));
      tip = tr("Fit the %1 model")
                .arg(QString::fromUtf8(name.data(), static_cast<qsizetype>(name.size())));
    }
    b->setToolTip(tip);
  }
  int checked = static_cast<int>(document_->model());
  if (lines) {
    const LineModel m = documentLineModel(document_->model(), document_->lineModel());
    checked = m == LineModel::Radial      ? kRadialId
              : m == LineModel::Quadratic ? static_cast<int>(ModelClass::Quadratic)
                                          : static_cast<int>(ModelClass::Auto);
  }
  if (QAbstractButton* b = models_->button(checked)) b->setChecked(true);
}
QAbstractButton* PairsPanel::modelButton(ModelClass model) const {
  return models_->button(static_cast<int>(model));
}
// Readers see the newest fit: a scheduled update is done first.
QString PairsPanel::modelScoresText() const {
  if (explanation_timer_->isActive()) const_cast<PairsPanel*>(this)->updateExplanation();
  return scores_->text();
}
QString PairsPanel::reasonText() const {
  if (explanation_timer_->isActive()) const_cast<PairsPanel*>(this)->updateExplanation();
  return reason_->text();
}

void PairsPanel::scheduleExplanation() {
  if (!explanation_timer_->isActive()) explanation_timer_->start();
}

void PairsPanel::updateExplanation() {
  explanation_timer_->stop();
  updateModelButtons();
  const bool shown = document_->photo() && !document_->manualCamera() && document_->fit().status.ok;
  // A line fit has no per-model pairs table (its record's reason says why its model).
  const bool scores = shown && !document_->linesDriveFit();
  scores_->setText(scores ? modelScoresHtml(document_->fit().record) : QString());
  reason_->setText(shown ? fitReasonText(document_->fit().record) : QString());
  scores_->setVisible(!scores_->text().isEmpty());
  reason_->setVisible(!reason_->text().isEmpty());
}

void PairsPanel::updateBanner() {
  QString text;
  if (!document_->photo()) {
    text = tr("Open a photo, then click a source point and its target.");
  } else if (document_->manualCamera()) {
    text = tr("Camera set by hand: the pairs are shown with its residuals but not fitted.");
  } else if (const int need = document_->pairsNeeded(); need > 0) {
    text = tr("Need %n more pair(s) for this model.", nullptr, need);
  } else if (!document_->fit().status.ok) {
    text = QString::fromStdString(document_->fit().status.message);
  } else if (document_->linesDriveFit()) {
    // Not the pairs fit's report ("quadratic, 0 matches, RMS 0 px"): the lines drive it.
    const FitRecord& r = document_->fit().record;
    const int lines = static_cast<int>(document_->lineBows().size());
    text = tr("Lines drive the fit: %1 lens from %n line(s) (Lines panel)", nullptr, lines)
               .arg(QString::fromStdString(r.model));
    if (r.matches > 0)
      text += tr("; %n pair(s) with them, RMS %1 px", nullptr, r.matches)
                  .arg(QString::number(r.rms_px, 'f', 2));
    else
      text += tr("; no pairs");
  } else {
    text = QString::fromStdString(document_->fit().report());
  }
  banner_->setText(text);
  const bool problem =
      document_->photo() && !document_->manualCamera() && !document_->fit().status.ok;
  banner_->setStyleSheet(problem ? "color: #d08000;" : "");
}

void PairsPanel::selectionFromDocument() {
  if (syncing_) return;
  syncing_ = true;
  QItemSelection sel;
  for (int row : document_->selection())
    sel.select(model_->index(row, 0), model_->index(row, PairsTableModel::ColumnCount - 1));
  table_->selectionModel()->select(sel, QItemSelectionModel::ClearAndSelect);
  if (!document_->selection().empty())
    table_->scrollTo(model_->index(document_->selection().back(), 0));
  syncing_ = false;
}

void PairsPanel::selectionToDocument() {
  if (syncing_) return;
  syncing_ = true;
  std::vector<int> rows;
  for (const QModelIndex& i : table_->selectionModel()->selectedRows()) rows.push_back(i.row());
  document_->setSelection(rows);
  syncing_ = false;
}

}  // namespace artcam::ui
