// SPDX-License-Identifier: Apache-2.0
// The lines table: one row per finished straight line (enabled, label, points, remaining bow
// after the fit in target px), like the pairs table. Toggling the check box and Delete push
// undo commands (line_commands.h), so one bad line is one Delete and one Ctrl+Z away, not a
// Ctrl+Z per clicked point. A line may be given a role, horizontal or vertical: the fit ignores
// it, and the table shows how far the corrected line is tilted from that direction. Above the
// table, what drives the fit: the line model and its reason, or why the lines are not fitted (a
// camera set by hand, a refused fit).
#pragma once

#include "core/model/line_trace.h"

#include <QAbstractTableModel>
#include <QWidget>

#include <vector>

class QLabel;
class QPushButton;
class QTableView;

namespace artcam::ui {

class Document;

class LinesTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  enum Column { Enabled, Label, Points, Bow, Role, Tilt, ColumnCount };

  explicit LinesTableModel(Document* document, QObject* parent = nullptr);

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;
  Qt::ItemFlags flags(const QModelIndex& index) const override;
  bool setData(const QModelIndex& index, const QVariant& value, int role) override;

 private:
  void refresh();

  Document* document_;
  int rows_ = 0;
};

class LinesPanel : public QWidget {
  Q_OBJECT

 public:
  explicit LinesPanel(Document* document, QWidget* parent = nullptr);

  QTableView* table() const { return table_; }
  QString summaryText() const;
  std::vector<int> selectedLines() const;
  void selectLine(int index);
  // Deletes the selected lines (one undo step); false when none is selected.
  bool deleteSelected();
  // Gives the selected lines a role (one undo step); false when nothing changed.
  bool setSelectedRole(LineRole role);

 private:
  void updateSummary();

  Document* document_;
  LinesTableModel* model_;
  QTableView* table_;
  QLabel* summary_;
  QPushButton* remove_;
  std::vector<QPushButton*> role_buttons_;
};

}  // namespace artcam::ui
