// SPDX-License-Identifier: Apache-2.0
// --quality N, --bit-depth 8|16|half|float, --colourspace input|srgb and --colourspace-in/-out
// NAME: how the commands that write a photo (export, warp, batch) read and encode it. One parser,
// so the three accept and refuse the same spellings.
#pragma once

#include "app/cli/args.h"
#include "core/io/image_io.h"
#include "core/sampling/filter.h"

#include <optional>
#include <string>

namespace artcam::cli {

// The pixel type named by a --bit-depth value ("8" → "uint8", "16" → "uint16", "half",
// "float"); throws UsageError for anything else.
std::string pixelTypeForBitDepth(const std::string& bit_depth);

// options.jpeg_subsampling from --subsampling 444|422|420 (absent: a JPEG input's, else 4:2:0).
// Sets options.jpeg_quality from --quality (a whole number 1..100; absent: left empty, so the
// writer keeps a JPEG input's quality, else 95) and options.pixel_type from --bit-depth
// (absent: left empty, the input's) and options.colour_space from --colourspace ("input", the
// default: integer outputs keep an ICC-tagged input's profile; "srgb": sRGB with an sRGB
// profile; image_io.h). Throws UsageError naming the option.
// --colourspace-out NAME sets options.ocio_colour_space (an OpenColorIO colour space,
// colour_spaces.h), refused beside --colourspace.
void parseWriteOptions(const Args& args, WriteImageOptions& options);

// --colourspace-in NAME: the OpenColorIO colour space the inputs are read in (empty: as each
// file says). Throws UsageError naming the option for a name the config does not have.
std::string parseColourSpaceIn(const Args& args);
// --edge transparent|extend|black (core/sampling/filter.h): what warp, batch and export read past
// the photo's edge; absent: transparent. Extend is what Hugin's nona and fulla and
// OpenImageIO's clamp do, but transparent stays the default: an ST map (export-map, fit
// --stmap) gives such pixels alpha 0, so `oiiotool --st_warp` with it reproduces `warp`.
// Throws UsageError for another value.
EdgeMode parseEdgeOption(const Args& args);
// --finish NAME (core/effects/finish.h): the marks after the render; absent: nullopt. With
// `allow_none`, "none" is taken (export: drop the project's finish) and returned as "".
// Throws UsageError for an unknown name, with the names and the nearest.
std::optional<std::string> parseFinishOption(const Args& args, bool allow_none = false);

}  // namespace artcam::cli
