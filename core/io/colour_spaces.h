// SPDX-License-Identifier: Apache-2.0
// Named OpenColorIO colour spaces for files (`--colourspace-in NAME`, `--colourspace-out NAME`):
// through OpenImageIO's ColorConfig, the config $OCIO names, else OpenImageIO's built-in one
// (linear, sRGB, Rec709). The engine's working space (linear Rec.709/sRGB primaries, D65;
// docs/architecture.md, "Images") is the config's colour space of the first of these names it
// has (as a name or an alias): lin_rec709, "Linear Rec.709 (sRGB)", "Utility - Linear - sRGB",
// linear; a config with none of them cannot be used, said in one line.
//
// Decisions:
// - A name read (ReadImageOptions::colour_space) overrides what the file says of itself (its
//   transfer, ICC profile, chromaticities): the file's values, integers scaled to 0..1, straight
//   colour, are converted from it into the working space; the photo is then linear and is
//   resampled in linear light (a plate in a log space is not resampled in its log numbers).
// - A name written (WriteImageOptions::ocio_colour_space) encodes the output from the working
//   space into it, straight colour, before quantising; the file is labelled with it
//   ("oiio:ColorSpace", which OpenEXR does not keep), with no ICC profile. An OpenEXR output
//   names the space's primaries (chromaticities) when the conversion into it is a matrix
//   (ACEScg, linear P3: probed on the basis and checked on other values), so a reader that
//   honours chromaticities reads its colours right; a space with a curve names none.
// - RGB only: OCIO converts colour triples; a grey image is refused in one line.
#pragma once

#include "core/model/status.h"

#include <string>

namespace artcam {

// Whether `name` is a colour space, alias or role of the config and the config has the working
// space. Fails in one line naming `option` and the config, listing a few of its colour spaces:
// "--colourspace-in: no colour space "X" in the OpenColorIO config built-in (linear, sRGB, …)".
Status checkColourSpace(const std::string& name, const std::string& option);

}  // namespace artcam
