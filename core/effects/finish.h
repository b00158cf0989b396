// SPDX-License-Identifier: Apache-2.0
// Marks: a non-photorealistic finishing step after the render, as the paper renders its
// photographic outputs "in a non-photorealistic style" (Figs 2 and 5) with existing methods.
// The methods are G'MIC's (libgmic, Debian's), by name; the render itself is untouched, the
// finish is applied to its output pixels.
#pragma once

#include "core/colour/stored_encoding.h"
#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/model/status.h"

#include <string>
#include <string_view>
#include <vector>

namespace artcam {

struct FinishInfo {
  std::string name;         // "pencil"
  std::string description;  // one line for --help and the studio
  std::string gmic;         // the G'MIC pipeline it runs
  // Draws random strokes: run seeded on one thread, so one photo always gets the same marks
  // (G'MIC's threads draw from the generator in whatever order they run).
  bool random = false;
};

// Every finish, in the order --help lists them.
const std::vector<FinishInfo>& finishes();
const FinishInfo* finishByName(std::string_view name);

// Applies the finish in place to an image of display values (sRGB-encoded 8/16-bit samples, or
// float in [0, 1] after the caller encodes linear light): the colour channels (grey or RGB)
// are marked, alpha is kept. Fails for an unknown name, an image too big for G'MIC's float
// copy (4 floats a pixel) or a G'MIC failure, each in one line.
Status applyFinish(const ImageView& image, std::string_view name);
// The same on a linear-light render (RGBA premultiplied, as the renderers give it): encoded as
// it will be stored (`encoding`: the photo's, core/colour/stored_encoding.h), marked, decoded
// back, so the marks are the ones `artcam warp --finish` draws on that file's values. What the
// export, the studio's preview and warp's float outputs call.
Status applyFinishLinear(ImageF& linear, const StoredEncoding& encoding, std::string_view name);

}  // namespace artcam
