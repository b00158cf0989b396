// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/lines_panel.h"

#include "core/fit/fit_lines.h"
#include "ui/document.h"
#include "ui/line_commands.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QPushButton>
#include <QTableView>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace artcam::ui {

LinesTableModel::LinesTableModel(Document* document, QObject* parent)
    : QAbstractTableModel(parent), document_(document) {
  rows_ = static_cast<int>(document_->lines().size());
  // linesChanged also follows every refit (the bows): rows are reset only when their count
  // changes, so a selection survives a point's drag.
  connect(document_, &Document::linesChanged, this, &LinesTableModel::refresh);
  connect(document_, &Document::cameraChanged, this, &LinesTableModel::refresh);
}

void LinesTableModel::refresh() {
  const int rows = static_cast<int>(document_->lines().size());
  if (rows != rows_) {
    beginResetModel();
    rows_ = rows;
    endResetModel();
  } else if (rows > 0) {
    emit dataChanged(index(0, 0), index(rows - 1, ColumnCount - 1));
  }
}

int LinesTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : rows_;
}

int LinesTableModel::columnCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : ColumnCount;
}

QVariant LinesTableModel::data(const QModelIndex& index, int role) const {
  if (!index.isValid() || index.row() >= static_cast<int>(document_->lines().size())) return {};
  const LineTrace& line = document_->lines()[static_cast<size_t>(index.row())];
  const int c = index.column();
  if (c == Enabled && role == Qt::CheckStateRole) return line.enabled ? Qt::Checked : Qt::Unchecked;
  if (role == Qt::TextAlignmentRole && (c == Points || c == Bow))
    return QVariant::fromValue(Qt::AlignRight | Qt::AlignVCenter);
  if (role == Qt::ToolTipRole && c == Tilt)
    return tr(
        "How far the corrected line is tilted from its role's direction (degrees); the "
        "fit does not level lines, it only straightens them");
  if (role == Qt::ToolTipRole && c == Bow)
    return tr(
        "The largest distance of the line's points, corrected, from their own straight "
        "line (px): what the camera leaves of its bow");
  if (role != Qt::DisplayRole) return {};
  switch (c) {
    case Label:
      return QString::fromStdString(line.label);
    case Points:
      return static_cast<int>(line.points.size());
    case Bow: {
      const auto bow = document_->lineBow(index.row());
      if (!bow) return line.enabled ? QString() : tr("off");
      return bow->mapped ? QString::number(bow->max_px, 'f', 2) : tr("unmapped");
    }
    case Role:
      return line.role == LineRole::Horizontal ? tr("H")
             : line.role == LineRole::Vertical ? tr("V")
                                               : QString();
    case Tilt: {
      const auto bow = document_->lineBow(index.row());
      if (line.role == LineRole::None || !bow || !bow->mapped) return QString();
      return QString::number(tiltFromRoleDeg(*bow, line.role), 'f', 2);
    }
    default:
      return {};
  }
}

QVariant LinesTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (role != Qt::DisplayRole) return {};
  if (orientation == Qt::Vertical) return section + 1;
  switch (section) {
    case Enabled:
      return tr("On");
    case Label:
      return tr("Line");
    case Points:
      return tr("Points");
    case Bow:
      return tr("Bow px");
    case Role:
      return tr("Role");
    case Tilt:
      return tr("Tilt °");
    default:
      return {};
  }
}

Qt::ItemFlags LinesTableModel::flags(const QModelIndex& index) const {
  Qt::ItemFlags f = QAbstractTableModel::flags(index);
  if (index.column() == Enabled) f |= Qt::ItemIsUserCheckable;
  return f;
}

bool LinesTableModel::setData(const QModelIndex& index, const QVariant& value, int role) {
  if (!index.isValid() || index.column() != Enabled || role != Qt::CheckStateRole) return false;
  if (index.row() >= static_cast<int>(document_->lines().size())) return false;
  const bool on = value.toInt() == Qt::Checked;
  if (on == document_->lines()[static_cast<size_t>(index.row())].enabled) return false;
  pushSetLineEnabled(document_, index.row(), on);
  return true;
}

LinesPanel::LinesPanel(Document* document, QWidget* parent)
    : QWidget(parent),
      document_(document),
      model_(new LinesTableModel(document, this)),
      table_(new QTableView(this)),
      summary_(new QLabel(this)),
      remove_(new QPushButton(tr("Delete"), this)) {
  table_->setModel(model_);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  table_->verticalHeader()->setDefaultSectionSize(22);
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  remove_->setToolTip(tr("Delete the selected lines (one undo step)"));
  remove_->setEnabled(false);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(remove_);
  const std::pair<LineRole, QString> roles[] = {
      {LineRole::Horizontal, tr("H")}, {LineRole::Vertical, tr("V")}, {LineRole::None, tr("–")}};
  for (const auto& [r, label] : roles) {
    auto* b = new QPushButton(label, this);
    b->setToolTip(r == LineRole::Horizontal ? tr("The selected lines are level in the scene")
                  : r == LineRole::Vertical ? tr("The selected lines are plumb in the scene")
                                            : tr("No role for the selected lines"));
    b->setEnabled(false);
    connect(b, &QPushButton::clicked, this, [this, role = r] { setSelectedRole(role); });
    role_buttons_.push_back(b);
    buttons->addWidget(b);
  }
  buttons->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(summary_);
  layout->addWidget(table_, 1);
  layout->addLayout(buttons);

  connect(remove_, &QPushButton::clicked, this, &LinesPanel::deleteSelected);
  const auto enableButtons = [this] {
    const bool any = !selectedLines().empty();
    remove_->setEnabled(any);
    for (QPushButton* b : role_buttons_) b->setEnabled(any);
  };
  connect(table_->selectionModel(), &QItemSelectionModel::selectionChanged, this, enableButtons);
  connect(model_, &QAbstractItemModel::modelReset, this, enableButtons);
  connect(document_, &Document::cameraChanged, this, &LinesPanel::updateSummary);
  connect(document_, &Document::linesChanged, this, &LinesPanel::updateSummary);
  updateSummary();
}

QString LinesPanel::summaryText() const { return summary_->text(); }

std::vector<int> LinesPanel::selectedLines() const {
  std::vector<int> rows;
  for (const QModelIndex& i : table_->selectionModel()->selectedRows()) rows.push_back(i.row());
  std::sort(rows.begin(), rows.end());
  return rows;
}

void LinesPanel::selectLine(int index) {
  if (index < 0 || index >= model_->rowCount()) {
    table_->clearSelection();
    return;
  }
  table_->selectRow(index);
}

bool LinesPanel::deleteSelected() { return pushDeleteLines(document_, selectedLines()); }

bool LinesPanel::setSelectedRole(LineRole role) {
  return pushSetLineRoles(document_, selectedLines(), role);
}

void LinesPanel::updateSummary() {
  QString text;
  if (document_->lines().empty()) {
    text =
        tr("No lines yet: with the Line tool, click along an edge that is straight in the "
           "scene and press Enter to end it.");
  } else if (document_->manualCamera()) {
    text = tr("Camera set by hand: the lines are drawn with its bows but not fitted.");
  } else if (!document_->linesDriveFit()) {
    text = tr("Every line is off: the pairs drive the fit.");
  } else if (!document_->fit().status.ok) {
    text = QString::fromStdString(document_->fit().status.message);
  } else {
    text =
        tr("Lines drive the fit: %1").arg(QString::fromStdString(document_->fit().record.reason));
  }
  summary_->setText(text);
}

}  // namespace artcam::ui
