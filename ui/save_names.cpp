// SPDX-License-Identifier: Apache-2.0
#include "ui/save_names.h"

#include <QDir>
#include <QFileInfo>

namespace artcam::ui {

QString proposedSavePath(const QString& photo_path, const QString& tail,
                         const QString& fallback_base) {
  if (photo_path.isEmpty()) return fallback_base + tail;
  const QFileInfo info(photo_path);
  return info.absoluteDir().filePath(info.completeBaseName() + tail);
}

}  // namespace artcam::ui
