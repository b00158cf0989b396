// SPDX-License-Identifier: Apache-2.0
#include "core/io/embedded_profile.h"

#include "core/colour/icc_profile.h"

namespace artcam {

Result<EmbeddedProfile> checkEmbeddedProfile(const std::vector<unsigned char>& bytes,
                                             int colour_channels, bool jpeg,
                                             const std::string& path) {
  using R = Result<EmbeddedProfile>;
  EmbeddedProfile decision;
  if (bytes.empty()) return R::success(std::move(decision));
  // A CMYK JPEG: the reader has already turned its ink values into RGB (without the profile),
  // so the profile no longer describes the pixels. They are read as sRGB, as untagged ones, and
  // no output is labelled with the CMYK profile (libpng refuses it; a JPEG viewer would apply
  // it to RGB values).
  if (jpeg && colour_channels == 3 && IccProfile::describesCmyk(bytes)) {
    decision.dropped =
        "its embedded CMYK ICC profile does not describe the RGB the reader made "
        "of its inks";
    return R::success(std::move(decision));
  }
  if (colour_channels != 1 && colour_channels != 3)
    return R::failure(path + ": cannot read: an ICC profile cannot describe its " +
                      std::to_string(colour_channels) + " colour channels");
  auto profile = IccProfile::fromBytes(bytes, colour_channels, path);
  if (!profile) return R::failure(profile.status.message);
  if (!profile->equivalentToSrgb())
    decision.converting = std::make_shared<const IccProfile>(std::move(*profile.value));
  return R::success(std::move(decision));
}

void recordEmbeddedProfile(const EmbeddedProfile& profile, ImageInfo& info) {
  if (profile.converting) {
    info.icc = profile.converting;
    info.srgb = false;
    info.colour_space = "ICC: " + profile.converting->description();
  } else if (!profile.dropped.empty()) {
    info.profile_dropped = profile.dropped;
    info.colour_space = "sRGB (CMYK turned into RGB by the reader; its profile not applied)";
  }
}

}  // namespace artcam
