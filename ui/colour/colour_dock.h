// SPDX-License-Identifier: Apache-2.0
// The Colour dock: colour calibration from patches picked on two
// photos. Open a reference photo; click a patch on the source view (the document's photo)
// and the matching patch on the reference view, in either order (a half pair waits in
// yellow; Esc drops it); drag a square to move it; Del deletes the selected samples. The
// table lists every pair with its colours and ΔE00 (before, and after the current colour
// block); "Fit colour" runs core's fitColourSamples off the GUI thread (model selection or a
// named model, optional robust MSAC) and sets the document's colour block by an undo command,
// so the preview and the export show it. Samples are kept in the project (parts/colour) and
// export as the CSV `artcam fit --block colour` reads.
#pragma once

#include "core/fit/fit_colour.h"
#include "ui/colour/colour_samples.h"

#include <QPointer>
#include <QWidget>

#include <optional>

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace artcam::ui {

class ColourFitJob;
class Document;
class ImageLoader;
class PatchView;
class Session;

class ColourDock : public QWidget {
  Q_OBJECT

 public:
  explicit ColourDock(Document* document, QWidget* parent = nullptr);
  ~ColourDock() override;

  // Keeps the samples and colour block in projects (parts/colour), autosaves and recoveries.
  void attachToSession(Session* session);

  ColourSampleModel* model() const { return model_; }
  PatchView* sourceView() const { return source_view_; }
  PatchView* referenceView() const { return reference_view_; }
  QTableWidget* table() const { return table_; }
  const std::optional<ColourFitSummary>& lastFit() const { return last_fit_; }
  QString report() const;
  bool isFitting() const;

  // The fit's settings (what the combo box and check box show).
  ColourFitOptions fitOptions() const;
  void setFitModel(ColourModel model);
  void setRobust(bool robust);

 public slots:
  // Reads the reference photo on a worker thread; opening it is one undo step.
  void openReference(const QString& path);
  void openReferenceDialog();
  // Runs the fit on the enabled samples (off the GUI thread); fitFinished follows.
  void fit();
  void clearColourBlock();
  // Written off the GUI thread; csvExported says how it ended (true: the write started).
  bool exportCsv(const QString& path);
  void exportCsvDialog();
  void deleteSelected();
  void setRadius(int radius);

 signals:
  void fitFinished(bool ok);
  void referenceLoaded(bool ok, const QString& message);
  void statusMessage(const QString& message);
  void csvExported(bool ok, const QString& message);
  // An opened project brought colour samples back (the window shows this dock).
  void samplesRestored();

 protected:
  void keyPressEvent(class QKeyEvent* event) override;

 private:
  void startReferenceLoad(const QString& path, bool undoable);
  void onPressed(bool reference_side, const Eigen::Vector2d& px);
  void onPressedMark(bool reference_side, int index);
  void onDragged(bool reference_side, const Eigen::Vector2d& px);
  void onFitted(const ColourFitSummary& summary, quint64 tag);
  void refreshViews();
  void refreshTable();
  void refreshReport();

  Document* document_;
  ColourSampleModel* model_;
  ColourFitJob* job_;
  PatchView* source_view_;
  PatchView* reference_view_;
  QTableWidget* table_;
  QSpinBox* radius_;
  QComboBox* model_box_;
  QCheckBox* robust_;
  QPushButton* fit_button_;
  QLabel* report_;
  QPointer<ImageLoader> loader_;
  bool loader_undoable_ = true;
  std::optional<Eigen::Vector2d> pending_source_, pending_reference_;  // half pairs (view state)
  std::optional<ColourFitSummary> last_fit_;
  QString message_;
  int drag_index_ = -1;
  bool drag_reference_ = false;
  int gesture_ = 0;
  bool updating_table_ = false;
};

}  // namespace artcam::ui
