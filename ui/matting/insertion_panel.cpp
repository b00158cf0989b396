// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_panel.h"

#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "ui/background_job.h"
#include "ui/document.h"
#include "ui/matting/board_view.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_preview.h"
#include "ui/matting/insertion_worker.h"
#include "ui/save_names.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>
#include <memory>
#include <optional>

namespace artcam::ui {

namespace {

// Runs `work` as a one-shot job of background_job.h and hands its Result to `done` on the
// owner's thread (not at all once the owner is gone); an exception becomes a failed Result.
template <class T, class Work, class Done>
void runOffThread(QObject* owner, Work work, Done done) {
  runInBackground(
      owner, [work = std::move(work)](JobContext&) mutable -> Result<T> { return work(); },
      [done = std::move(done)](JobOutcome<Result<T>> outcome) mutable {
        done(outcome.value ? std::move(*outcome.value)
                           : Result<T>::failure(outcome.error.toStdString()));
      });
}

QPushButton* button(const QString& text, const QString& tip, QWidget* parent) {
  auto* b = new QPushButton(text, parent);
  b->setToolTip(tip);
  return b;
}

// The photo the insertion's files are named after (save_names.h); empty without one.
QString photoPathOf(const InsertionModel* model) {
  const PhotoPtr& photo = model->document()->photo();
  return photo ? photo->path : QString();
}

}  // namespace

InsertionPanel::InsertionPanel(InsertionModel* model, InsertionPreview* preview, QWidget* parent)
    : QWidget(parent),
      model_(model),
      preview_(preview),
      graphic_label_(new QLabel(tr("none"), this)),
      board_width_(new QSpinBox(this)),
      board_height_(new QSpinBox(this)),
      squares_(new QSpinBox(this)),
      max_error_(new QDoubleSpinBox(this)),
      place_x_(new QDoubleSpinBox(this)),
      place_y_(new QDoubleSpinBox(this)),
      place_width_(new QDoubleSpinBox(this)),
      error_map_(new QCheckBox(tr("Show per-patch error map"), this)),
      matches_label_(new QLabel(this)),
      on_table_(new QCheckBox(tr("Clicks on the table"), this)),
      board_view_(new BoardView(model, this)),
      status_(new QLabel(this)),
      report_(new QPlainTextEdit(this)),
      tool_area_(new QVBoxLayout) {
  auto* layout = new QVBoxLayout(this);

  auto* graphic_row = new QHBoxLayout;
  QPushButton* load_graphic = button(tr("Graphic…"),
                                     tr("The image to insert (alpha is kept), "
                                        "drawn over the board's canonical view"),
                                     this);
  graphic_row->addWidget(load_graphic);
  graphic_row->addWidget(graphic_label_, 1);
  layout->addLayout(graphic_row);

  auto* form = new QFormLayout;
  auto* size_row = new QHBoxLayout;
  for (QSpinBox* s : {board_width_, board_height_}) {
    s->setRange(16, 16384);
    s->setKeyboardTracking(false);
    s->setSuffix(tr(" px"));
    size_row->addWidget(s);
  }
  board_width_->setToolTip(
      tr("Width of the board's canonical view (source pixels of the grid matches)"));
  board_height_->setToolTip(tr("Height of the board's canonical view"));
  form->addRow(tr("Board"), size_row);
  squares_->setRange(2, 200);
  squares_->setKeyboardTracking(false);
  squares_->setToolTip(tr("Squares along each side of the checkerboard"));
  form->addRow(tr("Squares"), squares_);
  max_error_->setRange(0.01, 50.0);
  max_error_->setSingleStep(0.05);
  max_error_->setDecimals(2);
  max_error_->setSuffix(tr(" px"));
  max_error_->setKeyboardTracking(false);
  max_error_->setToolTip(tr("Patches are split until each one's max error is below this"));
  form->addRow(tr("Max error"), max_error_);
  auto* place_row = new QHBoxLayout;
  for (QDoubleSpinBox* s : {place_x_, place_y_, place_width_}) {
    s->setRange(-16384.0, 16384.0);
    s->setDecimals(1);
    s->setKeyboardTracking(false);
    place_row->addWidget(s);
  }
  place_width_->setRange(0.0, 16384.0);
  place_width_->setSpecialValueText(tr("fill"));
  place_x_->setToolTip(tr("Left edge of the graphic on the board (board pixels)"));
  place_y_->setToolTip(tr("Top edge of the graphic on the board (board pixels)"));
  place_width_->setToolTip(
      tr("Width of the graphic on the board (board pixels, its aspect kept); "
         "\"fill\": stretched over the whole board"));
  form->addRow(tr("Graphic at"), place_row);
  layout->addLayout(form);

  auto* csv_row = new QHBoxLayout;
  QPushButton* import_csv = button(tr("Import Grid…"),
                                   tr("Grid matches from CSV (src_x,src_y,dst_x,dst_y: board "
                                      "pixels → photo pixels), e.g. from `artcam sample`"),
                                   this);
  QPushButton* export_csv = button(tr("Export Grid…"), tr("Save the grid matches as CSV"), this);
  csv_row->addWidget(import_csv);
  csv_row->addWidget(export_csv);
  layout->addLayout(csv_row);
  layout->addLayout(tool_area_);

  auto* edit_row = new QHBoxLayout;
  QPushButton* delete_match =
      button(tr("Delete Match"), tr("Remove the selected grid match (Del in the grid tool)"), this);
  QPushButton* clear_region = button(
      tr("Clear Region"), tr("Remove the marked region (the composite is then unlimited)"), this);
  edit_row->addWidget(delete_match);
  edit_row->addWidget(clear_region);
  layout->addLayout(edit_row);
  // Media (Fig 8: the water, then the air above it): each its own grid and region, the graphic
  // through all of them; the grid and region tools edit the one chosen here.
  auto* medium_row = new QHBoxLayout;
  medium_ = new QComboBox(this);
  medium_->setToolTip(
      tr("The medium the grid and region tools edit; the graphic is inserted "
         "through every medium, in this order"));
  QPushButton* new_medium = button(
      tr("New Medium"),
      tr("Another refracting or reflecting medium (the air above the water): its own grid and "
         "region; the media so far stay"),
      this);
  medium_row->addWidget(new QLabel(tr("Medium"), this));
  medium_row->addWidget(medium_, 1);
  medium_row->addWidget(new_medium);
  layout->addLayout(medium_row);
  layout->addWidget(on_table_);
  layout->addWidget(matches_label_);
  layout->addWidget(board_view_, 1);
  error_map_->setToolTip(
      tr("Outline each patch in the photo, green at 0 px to red at the max error (Shift+M)"));
  error_map_->setChecked(model_->errorMapVisible());
  layout->addWidget(error_map_);
  status_->setWordWrap(true);
  layout->addWidget(status_);
  report_->setReadOnly(true);
  report_->setMaximumBlockCount(200);
  report_->setToolTip(
      tr("The piecewise fit: patches, RMS/max error, seam gap, single-camera floor"));
  layout->addWidget(report_, 1);

  connect(load_graphic, &QPushButton::clicked, this, &InsertionPanel::loadGraphicDialog);
  connect(import_csv, &QPushButton::clicked, this, &InsertionPanel::importGridCsvDialog);
  connect(export_csv, &QPushButton::clicked, this, &InsertionPanel::exportGridCsvDialog);
  connect(delete_match, &QPushButton::clicked, this, &InsertionPanel::deleteSelectedMatch);
  connect(clear_region, &QPushButton::clicked, this, &InsertionPanel::clearRegion);
  connect(new_medium, &QPushButton::clicked, model_, &InsertionModel::addMedium);
  connect(medium_, &QComboBox::activated, model_, &InsertionModel::editMedium);
  connect(board_width_, &QSpinBox::valueChanged, this,
          [this](int w) { setBoardSize(w, board_height_->value()); });
  connect(board_height_, &QSpinBox::valueChanged, this,
          [this](int h) { setBoardSize(board_width_->value(), h); });
  connect(squares_, &QSpinBox::valueChanged, this, &InsertionPanel::setSquares);
  connect(max_error_, &QDoubleSpinBox::valueChanged, this, &InsertionPanel::setMaxError);
  for (QDoubleSpinBox* s : {place_x_, place_y_, place_width_})
    connect(s, &QDoubleSpinBox::valueChanged, this, [this] {
      GraphicPlacement p;
      p.origin = {place_x_->value(), place_y_->value()};
      p.width = place_width_->value();
      setPlacement(p);
    });
  connect(error_map_, &QCheckBox::toggled, model_, &InsertionModel::setErrorMapVisible);
  on_table_->setToolTip(
      tr("Grid clicks place board corners seen directly on the table, not in the reflection: "
         "four or more fix the board's homography, and the graphic is inserted on the table "
         "too (outside the region)"));
  connect(on_table_, &QCheckBox::toggled, model_, &InsertionModel::setClickingTable);
  connect(model_, &InsertionModel::selectionChanged, this,
          [this] { on_table_->setChecked(model_->clickingTable()); });
  connect(model_, &InsertionModel::errorMapVisibilityChanged, error_map_, &QCheckBox::setChecked);
  connect(model_, &InsertionModel::stateChanged, this, &InsertionPanel::syncFromModel);
  connect(preview_, &InsertionPreview::requested, this, &InsertionPanel::showFit);
  connect(preview_, &InsertionPreview::fitChanged, this, &InsertionPanel::showFit);
  connect(preview_, &InsertionPreview::compositeChanged, this, &InsertionPanel::showFit);
  connect(preview_, &InsertionPreview::failed, this,
          [this](const QString& m) { status_->setText(tr("Insertion failed: %1").arg(m)); });
  syncFromModel();
  showFit();
}

InsertionPanel::~InsertionPanel() = default;  // jobs in flight are cancelled, never waited for

QString InsertionPanel::reportText() const { return report_->toPlainText(); }
QString InsertionPanel::statusText() const { return status_->text(); }

void InsertionPanel::syncFromModel() {
  const InsertionState& s = model_->state();
  {
    const QSignalBlocker b1(board_width_), b2(board_height_), b3(squares_), b4(max_error_),
        b5(place_x_), b6(place_y_), b7(place_width_);
    place_x_->setValue(s.placement.origin.x());
    place_y_->setValue(s.placement.origin.y());
    place_width_->setValue(std::max(0.0, s.placement.width));
    board_width_->setValue(s.board_size.width);
    board_height_->setValue(s.board_size.height);
    squares_->setValue(s.squares);
    max_error_->setValue(s.max_error_px);
  }
  graphic_label_->setText(s.graphic ? QFileInfo(s.graphic_path).fileName() : tr("none"));
  graphic_label_->setToolTip(s.graphic_path);
  const int on_table = static_cast<int>(
      std::count_if(s.matches.begin(), s.matches.end(), [](const GridMatch& m) { return m.on_table; }));
  matches_label_->setText(tr("%n grid match(es)", nullptr, static_cast<int>(s.matches.size()) - on_table) +
                          (on_table > 0 ? tr(", %n on the table", nullptr, on_table) : QString()) +
                          (s.region.size() >= 3 ? tr(", region of %1 corners").arg(s.region.size())
                                                : tr(", no region")));
  {
    const QSignalBlocker block(medium_);
    medium_->clear();
    const std::vector<InsertionMedium> media = InsertionModel::media(s);
    for (size_t i = 0; i < media.size(); ++i) {
      const auto through = std::count_if(media[i].matches.begin(), media[i].matches.end(),
                                         [](const GridMatch& m) { return !m.on_table; });
      medium_->addItem(tr("%1: %n match(es)", nullptr, static_cast<int>(through)).arg(i + 1));
    }
    medium_->setCurrentIndex(s.current_medium);
  }
  board_view_->updateGeometry();
}

void InsertionPanel::showFit() {
  const InsertionFit& fit = preview_->fit();
  QString status;
  if (!fit.ok)
    status = fit.message;
  else
    status = tr("%1 patches, RMS %2 px, max %3 px%4 (fit %5 ms)")
                 .arg(fit.patches)
                 .arg(fit.rms_px, 0, 'f', 3)
                 .arg(fit.max_px, 0, 'f', 3)
                 .arg(fit.converged ? QString() : tr(" — some patches above the max error"))
                 .arg(fit.fit_ms, 0, 'f', 0);
  // The other media, each in a line after the edited one's.
  for (size_t i = 0, other = 0; i < fit.other_media.size() + 1; ++i) {
    if (static_cast<int>(i) == fit.current_medium) continue;
    const InsertionFit::Medium& m = fit.other_media[other++];
    status += QStringLiteral("\n") + (m.ok ? tr("Medium %1: %2 patches, max %3 px")
                                                 .arg(i + 1)
                                                 .arg(m.patches)
                                                 .arg(m.max_px, 0, 'f', 3)
                                           : tr("Medium %1: %2").arg(i + 1).arg(m.message));
  }
  if (!preview_->isCurrent()) status = tr("Fitting… ") + status;
  status_->setText(status);
  report_->setPlainText(fit.ok ? fit.report + (fit.table_report.isEmpty()
                                                    ? QString()
                                                    : QStringLiteral("\n") + fit.table_report)
                               : QString());
}

void InsertionPanel::reportError(const QString& title, const QString& message) {
  if (interactive_) QMessageBox::warning(this, title, message);
}

void InsertionPanel::reportLoadProblem(const QString& message) {
  reportError(tr("Insertion settings left out of the project"), message);
}

void InsertionPanel::loadGraphic(const QString& path, bool undoable) {
  status_->setText(tr("Loading %1…").arg(QFileInfo(path).fileName()));
  runOffThread<LoadedImage>(
      this, [p = path.toStdString()] { return readImage(p); },
      [this, path, undoable](Result<LoadedImage> r) {
        if (!r) {
          const QString m = QString::fromStdString(r.status.message);
          reportError(tr("Could not load the graphic"), m);
          emit graphicLoaded(false, m);
          return;
        }
        InsertionState next = model_->state();
        next.graphic = std::make_shared<const ImageF>(std::move(r->image));
        next.graphic_path = path;
        if (undoable)
          model_->edit(next, tr("Load Graphic"));
        else
          model_->setState(std::move(next));
        emit graphicLoaded(true, QString());
      });
}

void InsertionPanel::importGridCsv(const QString& path) {
  runOffThread<std::vector<PointMatch>>(
      this, [p = path.toStdString()] { return readMatchesCsv(p, 2); },
      [this, path](Result<std::vector<PointMatch>> r) {
        if (!r) {
          const QString m = QString::fromStdString(r.status.message);
          reportError(tr("Could not import the grid matches"), m);
          emit gridImported(false, m);
          return;
        }
        InsertionState next = model_->state();
        // The file holds matches through the object; the table clicks stay.
        std::erase_if(next.matches, [](const GridMatch& m) { return !m.on_table; });
        for (const PointMatch& m : *r)
          if (m.enabled) next.matches.push_back({m.source.head<2>(), m.target.head<2>()});
        model_->edit(next, tr("Import Grid Matches"));
        emit gridImported(
            true, tr("%1: %2 matches").arg(QFileInfo(path).fileName()).arg(model_->pointMatches().size()));
      });
}

void InsertionPanel::exportGridCsv(const QString& path) {
  runOffThread<bool>(
      this,
      [p = path.toStdString(), matches = model_->pointMatches()] {
        const Status s = writeMatchesCsv(p, matches);
        return s ? Result<bool>::success(true) : Result<bool>::failure(s.message);
      },
      [this](Result<bool> r) {
        const QString m = QString::fromStdString(r.status.message);
        if (!r) reportError(tr("Could not export the grid matches"), m);
        emit gridExported(r.ok(), m);
      });
}

void InsertionPanel::exportComposite(const QString& path) {
  const PhotoPtr photo = model_->document()->photo();
  const InsertionFit& fit = preview_->fit();
  const InsertionState& s = model_->state();
  if (!photo || !fit.rendersAny() || !s.graphic) {
    const QString m = tr("Nothing to export yet: a photo, a fitted grid and a graphic are needed.");
    reportError(tr("Could not export the inserted image"), m);
    emit compositeExported(false, m);
    return;
  }
  if (!photo->hasFullImage()) {
    // A first look (image_loader.h): the composite is of the full photo, so it waits for it.
    status_->setText(tr("Export of %1 waits for the full photo…").arg(QFileInfo(path).fileName()));
    model_->document()->whenFullImage(this, [this, path](bool ready) {
      if (ready) {
        exportComposite(path);
        return;
      }
      const QString m = tr("Export of %1 not made: the full photo was not decoded.").arg(path);
      reportError(tr("Could not export the inserted image"), m);
      status_->setText(m);
      emit compositeExported(false, m);
    });
    return;
  }
  status_->setText(tr("Exporting %1…").arg(QFileInfo(path).fileName()));
  runOffThread<bool>(
      this,
      [p = path.toStdString(), photo, fit, graphic = s.graphic, region = s.region,
       placement = s.placement] {
        const ImageF out =
            InsertionWorker::compositeMedia(photo->full.image, *graphic, fit, region, placement);
        const Status st = writeImage(p, out, &photo->full.info);
        return st ? Result<bool>::success(true) : Result<bool>::failure(st.message);
      },
      [this, path](Result<bool> r) {
        const QString m = r ? tr("Wrote %1").arg(path) : QString::fromStdString(r.status.message);
        if (!r) reportError(tr("Could not export the inserted image"), m);
        status_->setText(m);
        emit compositeExported(r.ok(), m);
      });
}

void InsertionPanel::exportCamera(const QString& path) {
  const InsertionFit& fit = preview_->fit();
  if (!fit.ok || !fit.camera || fit.camera->patches.empty()) {
    const QString m = tr("No fitted camera to export yet.");
    reportError(tr("Could not export the camera"), m);
    emit cameraExported(false, m);
    return;
  }
  runOffThread<bool>(
      this,
      [p = path.toStdString(), camera = fit.camera, matches = model_->pointMatches()] {
        // As `artcam insert --save-camera` writes it: the top level holds a plain camera
        // (the first patch's) and the matches, "patches" the piecewise camera.
        Artcam doc(camera->patches.front().camera);
        doc.matches = matches;
        doc.pieces = *camera;
        const Status st = writeArtcam(p, doc);
        return st ? Result<bool>::success(true) : Result<bool>::failure(st.message);
      },
      [this, path, medium = model_->state().current_medium,
       media = model_->mediumCount()](Result<bool> r) {
        // A chain of media is one camera each: say which one this file holds, never let it
        // pass for the whole chain.
        QString m = r ? tr("Wrote %1").arg(path) : QString::fromStdString(r.status.message);
        if (r && media > 1)
          m = tr("Wrote %1: medium %2 of %3 only. The graphic passes through every medium in "
                 "turn; choose each in the Medium box and export its camera too.")
                  .arg(path)
                  .arg(medium + 1)
                  .arg(media);
        if (!r) reportError(tr("Could not export the camera"), m);
        status_->setText(m);
        emit cameraExported(r.ok(), m);
      });
}

void InsertionPanel::exportCompositeDialog() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export Inserted Image"), proposedSavePath(photoPathOf(model_), "_inserted.png"),
      tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr);;All files (*)"));
  if (!path.isEmpty()) exportComposite(path);
}

void InsertionPanel::exportCameraDialog() {
  QString path = QFileDialog::getSaveFileName(
      this, tr("Export Piecewise Camera"),
      proposedSavePath(photoPathOf(model_), "_insertion.artcam"), tr("ARTcam (*.artcam)"));
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".artcam");
  exportCamera(path);
}

void InsertionPanel::setMaxError(double px) {
  InsertionState next = model_->state();
  next.max_error_px = px;
  model_->edit(next, tr("Max Error %1 px").arg(px));
}

void InsertionPanel::setBoardSize(int width, int height) {
  InsertionState next = model_->state();
  next.board_size = {width, height};
  model_->edit(next, tr("Board Size %1×%2").arg(width).arg(height));
}

void InsertionPanel::setSquares(int squares) {
  InsertionState next = model_->state();
  next.squares = squares;
  model_->edit(next, tr("Board Squares %1").arg(squares));
}

void InsertionPanel::setPlacement(const GraphicPlacement& placement) {
  InsertionState next = model_->state();
  next.placement = placement;
  model_->edit(next, tr("Place Graphic"));
}

void InsertionPanel::clearRegion() {
  InsertionState next = model_->state();
  next.region.clear();
  model_->edit(next, tr("Clear Region"));
}

void InsertionPanel::deleteSelectedMatch() {
  const int k = model_->selectedMatch();
  if (k < 0) return;
  InsertionState next = model_->state();
  next.matches.erase(next.matches.begin() + k);
  model_->setSelectedMatch(-1);
  model_->edit(next, tr("Delete Grid Match"));
}

void InsertionPanel::loadGraphicDialog() {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Graphic to Insert"), QString(),
      tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.bmp *.webp);;All files (*)"));
  if (!path.isEmpty()) loadGraphic(path);
}

void InsertionPanel::importGridCsvDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Import Grid Matches"), QString(),
                                                    tr("CSV (*.csv);;All files (*)"));
  if (!path.isEmpty()) importGridCsv(path);
}

void InsertionPanel::exportGridCsvDialog() {
  QString path = QFileDialog::getSaveFileName(this, tr("Export Grid Matches"),
                                              proposedSavePath(photoPathOf(model_), "_grid.csv"),
                                              tr("CSV (*.csv)"));
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".csv");
  exportGridCsv(path);
}

}  // namespace artcam::ui
