// SPDX-License-Identifier: Apache-2.0
// A file's embedded ICC profile checked against the pixels it describes: the one decision every
// image reader takes (the float path, the stored-value path, OpenImageIO's and the JPEG codec's
// readers), so each keeps, converts, drops or refuses the same profiles (image_io.h, "ICC
// profiles"; docs/architecture.md, "Embedded colour profiles on every path").
#pragma once

#include "core/io/image_io.h"
#include "core/model/status.h"

#include <memory>
#include <string>
#include <vector>

namespace artcam {

struct EmbeddedProfile {
  // The profile, when it describes the pixels and decodes otherwise than sRGB: the float path
  // converts through it, the stored-value path keeps it with the values it describes.
  std::shared_ptr<const IccProfile> converting;
  // Why a profile that does not describe the pixels as read is neither applied nor carried into
  // an output ("a CMYK profile on the RGB the reader made of a CMYK JPEG"); empty: not dropped.
  std::string dropped;
};

// `bytes`: the file's embedded profile (empty: none); `colour_channels`: the channels the image
// keeps, alpha aside; `jpeg`: the file is a JPEG (whose reader turns CMYK inks into RGB without
// the profile). Fails, in one line naming `path`, for a damaged profile or one of another colour
// space than the pixels (grey on RGB, Lab, CMYK on a TIFF's RGB): guessing would mislabel.
Result<EmbeddedProfile> checkEmbeddedProfile(const std::vector<unsigned char>& bytes,
                                             int colour_channels, bool jpeg,
                                             const std::string& path);

// Records the decision in what the reader says about the file: info.icc, srgb and colour_space
// for a converting profile, info.profile_dropped for a dropped one.
void recordEmbeddedProfile(const EmbeddedProfile& profile, ImageInfo& info);

}  // namespace artcam
