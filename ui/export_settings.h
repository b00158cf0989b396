// SPDX-License-Identifier: Apache-2.0
// The export options the studio keeps between sessions (QSettings, group "export": crop or
// fill and its colour, JPEG quality, bit depth, colour space, edge mode; the size is per export and
// is not kept), and the options a file's format can take (core's exportOptionsForOutput: a JPEG,
// which has no alpha, is filled with white rather than written with black corners).
#pragma once

#include "core/project/project_render.h"

#include <QString>

class QSettings;

namespace artcam::ui {

ExportOptions loadExportOptions(const QSettings& settings);
void saveExportOptions(QSettings& settings, const ExportOptions& options);

// exportOptionsForOutput (core/project/project_render.h) for a QString path.
ExportOptions exportOptionsForFile(ExportOptions options, const QString& path);

}  // namespace artcam::ui
