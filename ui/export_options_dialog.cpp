// SPDX-License-Identifier: Apache-2.0
#include "ui/export_options_dialog.h"

#include <QColorDialog>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include <cmath>

namespace artcam::ui {
namespace {

float linearFromSrgb(double c) {
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}
double srgbFromLinear(double c) {
  return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace

ExportOptionsDialog::ExportOptionsDialog(const ExportOptions& current, const QString& path,
                                         QWidget* parent)
    : QDialog(parent),
      base_(current),
      keep_(new QRadioButton(tr("Keep transparent"), this)),
      fill_(new QRadioButton(tr("Fill with"), this)),
      crop_(new QRadioButton(tr("Crop to the valid area"), this)),
      fill_colour_(new QPushButton(this)),
      colour_(Qt::white),
      quality_(new QSpinBox(this)),
      bit_depth_(new QComboBox(this)),
      colour_space_(new QComboBox(this)),
      edge_(new QComboBox(this)) {
  setWindowTitle(tr("Export options"));
  setObjectName("exportOptionsDialog");
  const QString suffix = QFileInfo(path).suffix().toLower();
  const bool jpeg = suffix == "jpg" || suffix == "jpeg";
  if (current.fill)
    colour_ = QColor::fromRgbF(srgbFromLinear((*current.fill)[0]), srgbFromLinear((*current.fill)[1]),
                               srgbFromLinear((*current.fill)[2]));
  // A JPEG has no alpha: keeping pixels transparent is not a choice there (export_settings.h),
  // so the fill (white unless one was chosen) is offered in its place.
  (current.crop_to_valid ? crop_ : current.fill || jpeg ? fill_ : keep_)->setChecked(true);
  keep_->setEnabled(!jpeg);
  crop_->setToolTip(tr("The largest rectangle in which every pixel has a preimage in the photo"));
  keep_->setToolTip(jpeg ? tr("JPEG has no transparency: fill or crop")
                         : tr("Pixels without a preimage stay transparent"));
  connect(fill_colour_, &QPushButton::clicked, this, [this] {
    const QColor c = QColorDialog::getColor(colour_, this, tr("Fill colour"));
    if (!c.isValid()) return;
    colour_ = c;
    fill_->setChecked(true);
    updateFillButton();
  });
  updateFillButton();
  auto* fill_row = new QHBoxLayout;
  fill_row->addWidget(fill_);
  fill_row->addWidget(fill_colour_);
  fill_row->addStretch(1);
  quality_->setRange(1, 100);
  quality_->setValue(current.write.jpeg_quality.value_or(95));
  quality_->setEnabled(jpeg);
  quality_->setToolTip(tr("JPEG quality (95 keeps fine detail; 85 is a common web setting)"));
  bit_depth_->addItem(tr("Same as the photo"), QString());
  bit_depth_->addItem(tr("8 bits"), QString("uint8"));
  if (!jpeg) {
    bit_depth_->addItem(tr("16 bits"), QString("uint16"));
    bit_depth_->addItem(tr("16-bit float (half)"), QString("half"));
    bit_depth_->addItem(tr("32-bit float"), QString("float"));
  }
  const int at = bit_depth_->findData(QString::fromStdString(current.write.pixel_type));
  bit_depth_->setCurrentIndex(at < 0 ? 0 : at);
  // As `artcam export --colourspace input|srgb`: integer files keep the ICC profile the photo
  // was converted from (an Adobe RGB photo stays Adobe RGB), or are encoded as sRGB with an
  // sRGB profile; float files hold the linear working space either way (image_io.h).
  colour_space_->setObjectName("colourSpace");
  colour_space_->addItem(tr("As the photo"), int(WriteImageOptions::ColourSpace::Input));
  colour_space_->addItem(tr("sRGB"), int(WriteImageOptions::ColourSpace::Srgb));
  colour_space_->setCurrentIndex(colour_space_->findData(int(current.write.colour_space)));
  colour_space_->setToolTip(
      tr("As the photo: 8- and 16-bit files keep the photo's ICC profile (Adobe RGB stays Adobe "
         "RGB). sRGB: encoded as sRGB with an sRGB profile, for the web. Float files hold linear "
         "Rec.709 either way."));
  // As `artcam export --edge`: what the filter reads past the photo's edge (filter.h).
  edge_->setObjectName("edge");
  edge_->addItem(tr("Fade to transparent"), int(EdgeMode::Transparent));
  edge_->addItem(tr("Extend the edge pixels"), int(EdgeMode::Extend));
  edge_->addItem(tr("Opaque black"), int(EdgeMode::Black));
  edge_->setCurrentIndex(edge_->findData(int(current.edge)));
  edge_->setToolTip(
      tr("Extend: the photo's last pixels continue to its edge, as Hugin and OpenImageIO "
         "resample. Fade: the last half pixel fades out. Black: composited over opaque black."));
  auto* form = new QFormLayout;
  form->addRow(tr("Pixels outside the photo"), keep_);
  form->addRow(QString(), fill_row);
  form->addRow(QString(), crop_);
  form->addRow(tr("JPEG quality"), quality_);
  form->addRow(tr("Bit depth"), bit_depth_);
  form->addRow(tr("Colour space"), colour_space_);
  form->addRow(tr("Photo's edge"), edge_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);
}

void ExportOptionsDialog::updateFillButton() {
  fill_colour_->setText(colour_.name());
  fill_colour_->setStyleSheet(QString("background-color: %1").arg(colour_.name()));
}

ExportOptions ExportOptionsDialog::options() const {
  ExportOptions o = base_;
  o.crop_to_valid = crop_->isChecked();
  o.fill.reset();
  if (fill_->isChecked())
    o.fill = std::array<float, 4>{linearFromSrgb(colour_.redF()), linearFromSrgb(colour_.greenF()),
                                  linearFromSrgb(colour_.blueF()), 1.0f};
  if (quality_->isEnabled()) o.write.jpeg_quality = quality_->value();
  o.write.pixel_type = bit_depth_->currentData().toString().toStdString();
  o.write.colour_space =
      static_cast<WriteImageOptions::ColourSpace>(colour_space_->currentData().toInt());
  o.edge = static_cast<EdgeMode>(edge_->currentData().toInt());
  return o;
}

std::optional<ExportOptions> ExportOptionsDialog::ask(const ExportOptions& current,
                                                      const QString& path, QWidget* parent) {
  ExportOptionsDialog dialog(current, path, parent);
  if (dialog.exec() != QDialog::Accepted) return std::nullopt;
  return dialog.options();
}

}  // namespace artcam::ui
