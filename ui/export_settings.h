// SPDX-License-Identifier: Apache-2.0
// The export options the studio keeps between sessions (QSettings, group "export": crop or
// fill and its colour, JPEG quality, bit depth, colour space; the size is per export and is not
// kept), and the options a file's format can take.
//
// Decisions:
// - A JPEG has no alpha, so "keep transparent" cannot be kept there: the pixels without a
//   preimage are filled with white, as an image editor flattens onto its white background
//   when saving a layer with transparency as JPEG. Black corners written without a word looked
//   like a broken camera. The export's status line says how many pixels were filled.
#pragma once

#include "core/project/project_render.h"

#include <QString>

#include <array>

class QSettings;

namespace artcam::ui {

// Linear white, the fill of a format without alpha when none was chosen.
inline constexpr std::array<float, 4> kFlattenFill = {1.0f, 1.0f, 1.0f, 1.0f};

ExportOptions loadExportOptions(const QSettings& settings);
void saveExportOptions(QSettings& settings, const ExportOptions& options);

// Whether the file's format (by its extension) holds alpha: false for JPEG.
bool formatHoldsAlpha(const QString& path);
// `options` for writing `path`: a format without alpha gets kFlattenFill when the options keep
// the pixels without a preimage transparent (no fill, no crop).
ExportOptions exportOptionsForFile(ExportOptions options, const QString& path);

}  // namespace artcam::ui
