// SPDX-License-Identifier: Apache-2.0
#include "ui/studio_wording.h"

#include <QCoreApplication>

namespace artcam::ui {

QString studioWording(const QString& message) {
  struct Advice {
    const char* cli;
    const char* studio;
  };
  static const Advice advice[] = {
      {"give a depth image (artcam warp --depth FILE)",
       QT_TRANSLATE_NOOP("StudioWording",
                         "paint depth planes with three depths each (Depth panel) or use File ▸ "
                         "Load Depth Map…")},
  };
  QString out = message;
  for (const Advice& a : advice)
    out.replace(QLatin1String(a.cli), QCoreApplication::translate("StudioWording", a.studio));
  return out;
}

}  // namespace artcam::ui
