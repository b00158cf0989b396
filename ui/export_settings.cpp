// SPDX-License-Identifier: Apache-2.0
#include "ui/export_settings.h"

#include <QSettings>
#include <QVariantList>

namespace artcam::ui {
namespace {

const char kCrop[] = "export/cropToValid";
const char kFill[] = "export/fill";  // four linear floats, or absent: keep transparent
const char kQuality[] = "export/jpegQuality";
const char kPixelType[] = "export/pixelType";
const char kColourSpace[] = "export/colourSpace";
const char kEdge[] = "export/edge";  // filter.h's names; absent or unknown: transparent

}  // namespace

ExportOptions loadExportOptions(const QSettings& settings) {
  ExportOptions o;
  o.crop_to_valid = settings.value(kCrop, false).toBool();
  const QVariantList fill = settings.value(kFill).toList();
  if (fill.size() == 4) {
    std::array<float, 4> f{};
    bool all = true;
    for (int i = 0; i < 4; ++i) {
      bool ok = false;
      const double v = fill[i].toDouble(&ok);
      all = all && ok && v >= 0.0 && v <= 1.0;  // a hand-edited file must not make a bad fill
      f[static_cast<size_t>(i)] = static_cast<float>(v);
    }
    if (all) o.fill = f;
  }
  bool ok = false;
  const int quality = settings.value(kQuality).toInt(&ok);
  if (ok && quality >= 1 && quality <= 100) o.write.jpeg_quality = quality;
  const QString type = settings.value(kPixelType).toString();
  if (type == "uint8" || type == "uint16" || type == "half" || type == "float")
    o.write.pixel_type = type.toStdString();
  o.write.colour_space = settings.value(kColourSpace).toString() == "srgb"
                             ? WriteImageOptions::ColourSpace::Srgb
                             : WriteImageOptions::ColourSpace::Input;
  if (const auto edge = edgeModeFromName(settings.value(kEdge).toString().toStdString()))
    o.edge = *edge;
  return o;
}

void saveExportOptions(QSettings& settings, const ExportOptions& o) {
  settings.setValue(kCrop, o.crop_to_valid);
  if (o.fill)
    settings.setValue(kFill, QVariantList{(*o.fill)[0], (*o.fill)[1], (*o.fill)[2], (*o.fill)[3]});
  else
    settings.remove(kFill);
  if (o.write.jpeg_quality)
    settings.setValue(kQuality, *o.write.jpeg_quality);
  else
    settings.remove(kQuality);
  settings.setValue(kPixelType, QString::fromStdString(o.write.pixel_type));
  settings.setValue(kColourSpace, o.write.colour_space == WriteImageOptions::ColourSpace::Srgb
                                      ? "srgb"
                                      : "input");
  settings.setValue(kEdge, QString::fromUtf8(edgeModeName(o.edge).data(),
                                             static_cast<int>(edgeModeName(o.edge).size())));
}

ExportOptions exportOptionsForFile(ExportOptions options, const QString& path) {
  return exportOptionsForOutput(std::move(options), path.toStdString());
}

}  // namespace artcam::ui
