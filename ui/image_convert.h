// SPDX-License-Identifier: Apache-2.0
// Conversions between the engine's ImageF (linear light, premultiplied alpha) and
// what Qt paints (8-bit sRGB QImage). Only the GUI needs them, so they live in ui/, not core/.
#pragma once

#include "core/model/image.h"

#include <QImage>

namespace artcam::ui {

// 8-bit sRGB, Format_ARGB32_Premultiplied (QPainter's fast path). The sRGB encoding goes
// through a 4096-entry table of linear values; colour is un-premultiplied before encoding and
// re-premultiplied after, so edges of transparent regions keep their hue.
// 1 channel: grey; 2: grey + alpha; 3: RGB; 4: RGBA (alpha where image.alpha_channel says).
QImage qimageFromLinear(const ImageF& image);

// Box average over integer blocks so the longer side is at most max_side (a copy when it is
// already small enough). Averaging premultiplied values is the correct filter for them.
ImageF boxDownscale(const ImageF& image, int max_side);

}  // namespace artcam::ui
