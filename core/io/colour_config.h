// SPDX-License-Identifier: Apache-2.0
// The image module's OpenColorIO conversions (io room, module only; colour_spaces.h says the
// decisions): the readers and writers convert through these.
#pragma once

#include "core/colour/chromaticities.h"
#include "core/model/status.h"

#include <cstddef>
#include <optional>
#include <string>

namespace artcam::io_colour {

Status checkColourSpace(const std::string& name, const std::string& option);

// In place over `pixels` interleaved pixels of `channels` floats (3, or 4 with alpha last),
// straight colour: from colour space `name` into the working space, or back. Fails in one line
// (`what`: "path: cannot read") when the config cannot make the conversion.
Status toWorking(const std::string& name, float* data, size_t pixels, int channels,
                 const std::string& what);
Status fromWorking(const std::string& name, float* data, size_t pixels, int channels,
                   const std::string& what);

// The chromaticities of colour space `name` when the config's map into it from the working space
// is linear (a matrix: ACEScg, linear P3), so an OpenEXR output in it can name its primaries;
// empty for a space with a curve (sRGB, a log space) or when the config cannot convert.
std::optional<Chromaticities> linearChromaticities(const std::string& name);

}  // namespace artcam::io_colour
