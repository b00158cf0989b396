// SPDX-License-Identifier: Apache-2.0
// The canvas cursor of a tool: a crosshair whose hot spot is the exact click point (pixel
// precision matters for every tool), tagged with the tool's one-letter key in its corner, so
// the tool in use is visible at the cursor itself and tools tell apart at a glance.
#pragma once

#include <QCursor>
#include <QString>

namespace artcam::ui {

QCursor toolCursor(const QString& tag);

}  // namespace artcam::ui
