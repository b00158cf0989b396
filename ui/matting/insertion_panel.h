// SPDX-License-Identifier: Apache-2.0
// The Insertion dock panel: the graphic to insert (loaded off the GUI
// thread), the board's canonical size and squares, grid matches imported from / exported to
// CSV (`src_x,src_y,dst_x,dst_y`: board pixels → photo pixels, as `artcam sample` writes
// them), the fit's max error, the error-map toggle, the board view that picks the corner the
// next photo click matches, and the fit report. The fit itself refits in a worker after every
// edit (InsertionPreview). Every edit is one undo step on the document's stack; file errors
// are dialogs naming the file and the cause (or only signals, when not interactive).
#pragma once

#include "ui/matting/graphic_placement.h"

#include <QString>
#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPlainTextEdit;
class QSpinBox;
class QVBoxLayout;

namespace artcam::ui {

class BoardView;
class InsertionModel;
class InsertionPreview;

class InsertionPanel : public QWidget {
  Q_OBJECT

 public:
  InsertionPanel(InsertionModel* model, InsertionPreview* preview, QWidget* parent = nullptr);
  ~InsertionPanel() override;  // cancels file jobs in flight (background_job.h); never waits

  void setInteractive(bool interactive) { interactive_ = interactive; }
  BoardView* boardView() const { return board_view_; }
  QString reportText() const;
  QString statusText() const;
  QComboBox* mediumBox() const { return medium_; }
  // Where the tool buttons go (the studio adds its tool actions here).
  QVBoxLayout* toolArea() const { return tool_area_; }

 public slots:
  // undoable = false: part of opening a project (no undo step, the document stays clean).
  void loadGraphic(const QString& path, bool undoable = true);
  // A problem with the insertion part of an opened project: shown like the panel's errors.
  void reportLoadProblem(const QString& message);
  void importGridCsv(const QString& path);
  void exportGridCsv(const QString& path);
  // The graphic inserted into the FULL-resolution photo (the photo's format and metadata),
  // and the piecewise camera as a .artcam file; both written off the GUI thread.
  void exportComposite(const QString& path);
  void exportCamera(const QString& path);
  void setMaxError(double px);
  void setBoardSize(int width, int height);
  void setSquares(int squares);
  void setPlacement(const artcam::ui::GraphicPlacement& placement);
  void clearRegion();
  void deleteSelectedMatch();
  void loadGraphicDialog();
  void importGridCsvDialog();
  void exportGridCsvDialog();
  void exportCompositeDialog();
  void exportCameraDialog();

 signals:
  void graphicLoaded(bool ok, const QString& message);
  void gridImported(bool ok, const QString& message);
  void gridExported(bool ok, const QString& message);
  void compositeExported(bool ok, const QString& message);
  void cameraExported(bool ok, const QString& message);

 private:
  void syncFromModel();
  void showFit();
  void reportError(const QString& title, const QString& message);

  InsertionModel* model_;
  InsertionPreview* preview_;
  bool interactive_ = true;
  QLabel* graphic_label_;
  QSpinBox* board_width_;
  QSpinBox* board_height_;
  QSpinBox* squares_;
  QDoubleSpinBox* max_error_;
  QDoubleSpinBox* place_x_;
  QDoubleSpinBox* place_y_;
  QDoubleSpinBox* place_width_;
  QCheckBox* error_map_;
  QLabel* matches_label_;
  QCheckBox* on_table_;
  QComboBox* medium_;
  BoardView* board_view_;
  QLabel* status_;
  QPlainTextEdit* report_;
  QVBoxLayout* tool_area_;
};

}  // namespace artcam::ui
