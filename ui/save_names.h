// SPDX-License-Identifier: Apache-2.0
// The file name every save dialog proposes: beside the photo, its base name and what is saved
// ("street.jpg" → "street_camera.artcam"), as image editors propose "name copy" beside the
// original, so a save is one Enter. Without a photo, the bare name in the dialog's last folder.
#pragma once

#include <QString>

namespace artcam::ui {

// `tail` is what follows the base name, extension included: "_camera.artcam", ".artcamproj".
// `fallback_base` replaces the base name when there is no photo ("untitled").
QString proposedSavePath(const QString& photo_path, const QString& tail,
                         const QString& fallback_base = QStringLiteral("untitled"));

}  // namespace artcam::ui
