// SPDX-License-Identifier: Apache-2.0
// The export options image editors offer after the file name: what to do with pixels the camera
// leaves without a preimage (keep them transparent, fill them with a colour, or crop to the
// largest rectangle of valid pixels, as Hugin's "crop to valid area"), the JPEG quality, the
// bit depth and the colour space (the photo's own ICC profile, or sRGB for the web). The choices
// persist for the next exports and sessions (Session::exportOptions, export_settings.h). A JPEG
// cannot keep pixels transparent: "Keep transparent" is disabled and the fill is chosen.
#pragma once

#include "core/project/project_render.h"

#include <QDialog>

#include <optional>

class QCheckBox;
class QComboBox;
class QPushButton;
class QRadioButton;
class QSpinBox;

namespace artcam::ui {

class ExportOptionsDialog : public QDialog {
  Q_OBJECT

 public:
  // `path` decides which options apply (quality only for JPEG, 16-bit not for JPEG).
  ExportOptionsDialog(const ExportOptions& current, const QString& path, QWidget* parent = nullptr);
  ExportOptions options() const;

  // Shows the dialog; nullopt when cancelled.
  static std::optional<ExportOptions> ask(const ExportOptions& current, const QString& path,
                                          QWidget* parent);

 private:
  void updateFillButton();

  ExportOptions base_;
  QRadioButton* keep_;
  QRadioButton* fill_;
  QRadioButton* crop_;
  QPushButton* fill_colour_;
  QColor colour_;
  QSpinBox* quality_;
  QComboBox* bit_depth_;
  QComboBox* colour_space_;
  QComboBox* edge_;
};

}  // namespace artcam::ui
