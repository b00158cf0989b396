// SPDX-License-Identifier: Apache-2.0
// Lens ▸ From Database…: choose a lens of the lensfun database (core/lens) and the settings of
// `artcam lens camera` for the open photo. The list searches as you type (every word must
// begin a word of the lens's name, else lensfun's own match, LensDatabase::search); with the
// field empty it shows the lenses LensDatabase::lookUp finds for the photo's EXIF (the lookup
// `artcam lens camera --from` makes: its first lens is the CLI's choice), the crop factor
// starts at that of the camera lensfun knows, the focal length and the aperture at the EXIF
// ones (vignetting needs the aperture; without one it is left out and the summary says so).
// The dialog only chooses:
// Session makes the camera off the GUI thread and sets it as the document's camera.
#pragma once

#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"

#include <QDialog>

#include <memory>

class QCheckBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;

namespace artcam::ui {

class LensDialog : public QDialog {
  Q_OBJECT

 public:
  LensDialog(std::shared_ptr<const LensDatabase> database, FrameSize photo_size,
             const LensHint& hint, QWidget* parent = nullptr);

  // The chosen lens and settings; options().lens is empty while no lens is selected.
  LensCameraOptions options() const;

  QLineEdit* searchField() const { return search_; }
  QListWidget* lensList() const { return list_; }
  QDoubleSpinBox* focalField() const { return focal_; }
  QDoubleSpinBox* apertureField() const { return aperture_; }
  QCheckBox* vignettingBox() const { return vignetting_; }

 private:
  void fill();             // the list for the search text (or the suggestions)
  void selectionChanged();  // focal range and the description of the selected lens

  std::shared_ptr<const LensDatabase> database_;
  FrameSize photo_size_;
  std::vector<LensEntry> suggestions_;
  std::vector<LensEntry> shown_;
  QLineEdit* search_;
  QListWidget* list_;
  QLabel* about_;
  QDoubleSpinBox* focal_;
  QDoubleSpinBox* crop_;
  QDoubleSpinBox* aperture_;
  QCheckBox* distort_;
  QCheckBox* tca_;
  QCheckBox* vignetting_;
  QDialogButtonBox* buttons_;
};

}  // namespace artcam::ui
