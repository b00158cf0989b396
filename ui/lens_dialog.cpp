// SPDX-License-Identifier: Apache-2.0
#include "ui/lens_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QVBoxLayout>

namespace artcam::ui {

LensDialog::LensDialog(std::shared_ptr<const LensDatabase> database, FrameSize photo_size,
                       const LensHint& hint, QWidget* parent)
    : QDialog(parent), database_(std::move(database)), photo_size_(photo_size) {
  setWindowTitle(tr("Lens from Database"));
  auto* layout = new QVBoxLayout(this);
  search_ = new QLineEdit(this);
  search_->setObjectName("lensSearch");
  search_->setPlaceholderText(tr("Type words of the lens name (e.g. canon 10-22)"));
  search_->setClearButtonEnabled(true);
  layout->addWidget(search_);
  list_ = new QListWidget(this);
  list_->setObjectName("lensList");
  layout->addWidget(list_, 1);
  about_ = new QLabel(this);
  about_->setObjectName("lensAbout");
  about_->setWordWrap(true);
  layout->addWidget(about_);

  auto* form = new QFormLayout;
  focal_ = new QDoubleSpinBox(this);
  focal_->setObjectName("lensFocal");
  focal_->setDecimals(1);
  focal_->setRange(0.1, 2000.0);
  focal_->setSuffix(tr(" mm"));
  focal_->setValue(hint.focal_mm > 0 ? hint.focal_mm : 50.0);
  form->addRow(tr("Focal length:"), focal_);
  crop_ = new QDoubleSpinBox(this);
  crop_->setObjectName("lensCrop");
  crop_->setDecimals(3);
  crop_->setRange(0.0, 20.0);
  crop_->setSpecialValueText(tr("the lens's calibration"));
  crop_->setValue(0.0);
  crop_->setToolTip(tr("The crop factor of the camera the photo was taken with"));
  form->addRow(tr("Crop factor:"), crop_);
  aperture_ = new QDoubleSpinBox(this);
  aperture_->setObjectName("lensAperture");
  aperture_->setDecimals(1);
  aperture_->setRange(0.0, 64.0);
  aperture_->setSingleStep(0.1);
  aperture_->setPrefix(tr("f/"));
  aperture_->setSpecialValueText(tr("not known"));
  aperture_->setValue(hint.aperture > 0 ? hint.aperture : 0.0);
  aperture_->setToolTip(tr("The f-number the photo was taken at: vignetting depends on it"));
  form->addRow(tr("Aperture:"), aperture_);
  distort_ = new QCheckBox(tr("Simulate the lens (distort) instead of correcting it"), this);
  distort_->setObjectName("lensDistort");
  form->addRow(distort_);
  tca_ = new QCheckBox(tr("Chromatic aberration (TCA) as colour layers, where the database has it"),
                       this);
  tca_->setObjectName("lensTca");
  tca_->setChecked(true);
  form->addRow(tca_);
  vignetting_ = new QCheckBox(tr("Vignetting as a gain on colour, where the database has it "
                                 "(needs the aperture)"),
                              this);
  vignetting_->setObjectName("lensVignetting");
  vignetting_->setChecked(true);
  form->addRow(vignetting_);
  layout->addLayout(form);

  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Use Lens"));
  layout->addWidget(buttons_);
  connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);

  // The lookup `artcam lens camera --from` makes: its first lens is the one the CLI takes, and
  // the crop factor of the camera lensfun knows from the EXIF is the one it uses.
  const PhotoLensLookup lookup = database_->lookUp(hint);
  suggestions_ = lookup.lenses;
  if (lookup.camera_crop > 0) crop_->setValue(lookup.camera_crop);
  connect(search_, &QLineEdit::textChanged, this, &LensDialog::fill);
  connect(list_, &QListWidget::currentRowChanged, this, &LensDialog::selectionChanged);
  connect(list_, &QListWidget::itemDoubleClicked, this, &QDialog::accept);
  fill();
  resize(640, 520);
}

void LensDialog::fill() {
  const std::string text = search_->text().trimmed().toStdString();
  shown_ = text.empty() ? suggestions_ : database_->search(text, 200);
  list_->clear();
  for (const LensEntry& e : shown_) list_->addItem(QString::fromStdString(e.describe()));
  if (!shown_.empty()) list_->setCurrentRow(0);
  selectionChanged();
}

void LensDialog::selectionChanged() {
  const int row = list_->currentRow();
  const bool chosen = row >= 0 && row < static_cast<int>(shown_.size());
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(chosen);
  if (!chosen) {
    about_->setText(search_->text().trimmed().isEmpty()
                        ? tr("No suggestion from the photo's EXIF: type to search the %1 lenses.")
                              .arg(database_->size())
                        : tr("No lens matches, not even by lensfun's loose search."));
    return;
  }
  const LensEntry& e = shown_[static_cast<size_t>(row)];
  // The focal length stays the user's (or the EXIF's) while it is in the lens's range.
  if (focal_->value() < e.min_focal_mm || focal_->value() > e.max_focal_mm)
    focal_->setValue(e.min_focal_mm);
  about_->setText(tr("%1 by %2, %3. The camera is fitted to lensfun's model for a %4×%5 photo "
                     "and its error is reported.")
                      .arg(QString::fromStdString(e.model), QString::fromStdString(e.maker),
                           QString::fromStdString(e.type))
                      .arg(photo_size_.width)
                      .arg(photo_size_.height));
}

LensCameraOptions LensDialog::options() const {
  LensCameraOptions o;
  const int row = list_->currentRow();
  if (row >= 0 && row < static_cast<int>(shown_.size())) {
    const LensEntry& e = shown_[static_cast<size_t>(row)];
    o.lens = e.model;
    // Without a crop of its own, the calibration shown is the one used.
    o.crop = crop_->value() > 0 ? crop_->value() : e.crop_factor;
  }
  o.focal_mm = focal_->value();
  o.size = photo_size_;
  o.distort = distort_->isChecked();
  o.tca = tca_->isChecked();
  o.vignetting = vignetting_->isChecked();
  o.aperture = aperture_->value();
  return o;
}

}  // namespace artcam::ui
