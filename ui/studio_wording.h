// SPDX-License-Identifier: Apache-2.0
// Core's messages advise the command line where a renderer lacks an input ("give a depth image
// (artcam warp --depth FILE)"); in the studio the same lack has a menu or a panel that fills it.
// studioWording swaps such advice for the studio's action and leaves every other text as it is.
#pragma once

#include <QString>

namespace artcam::ui {

QString studioWording(const QString& message);

}  // namespace artcam::ui
