// SPDX-License-Identifier: Apache-2.0
// The pairs table: one row per pair (enabled, source x/y, target x/y, residual), edited both
// ways: typing a coordinate or toggling the check box pushes an undo command; canvas edits
// and selection show up here through the document's signals. A banner says how many more
// pairs the chosen model needs while it is underdetermined, or why the fit failed. Under the
// table, a one-click model selector (the same undoable model change as the Model menu) and why
// the fit has its model: each model's error and the fit's reason (fit_explanation.h).
#pragma once

#include "core/fit/fit_image.h"

#include <QAbstractTableModel>
#include <QTimer>
#include <QWidget>

class QAbstractButton;
class QButtonGroup;
class QLabel;
class QTableView;

namespace artcam::ui {

class Document;

class PairsTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  enum Column { Enabled, SourceX, SourceY, TargetX, TargetY, Residual, ColumnCount };

  explicit PairsTableModel(Document* document, QObject* parent = nullptr);

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;
  Qt::ItemFlags flags(const QModelIndex& index) const override;
  bool setData(const QModelIndex& index, const QVariant& value, int role) override;

 private:
  Document* document_;
};

class PairsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PairsPanel(Document* document, QWidget* parent = nullptr);

  QTableView* table() const { return table_; }
  QString bannerText() const;
  QAbstractButton* modelButton(ModelClass model) const;
  // The model row's Radial button: a lens for straight lines, enabled while lines drive the fit.
  QAbstractButton* radialButton() const;
  QString modelScoresText() const;  // the per-model table (rich text)
  QString reasonText() const;

 private:
  void updateBanner();
  // Which model buttons apply: with lines driving the fit, Auto, Radial and Quadr.; else every
  // pairs model. The checked one follows the document's choice.
  void updateModelButtons();
  void chooseModel(int id);
  void updateExplanation();
  // The explanation follows fit results at most every kExplanationMs: rich-text labels re-lay out
  // the dock, and during a drag a fit result arrives on every mouse move.
  void scheduleExplanation();
  static constexpr int kExplanationMs = 100;
  // Lines of the explanation's fixed-height box: the score table of the six models and a
  // two-line reason; more scrolls.
  static constexpr int kExplanationLines = 10;
  void selectionFromDocument();
  void selectionToDocument();

  Document* document_;
  PairsTableModel* model_;
  QTableView* table_;
  QLabel* banner_;
  QButtonGroup* models_;
  QLabel* scores_;
  QLabel* reason_;
  QTimer* explanation_timer_;
  bool syncing_ = false;
};

}  // namespace artcam::ui
