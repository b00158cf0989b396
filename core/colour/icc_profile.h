// SPDX-License-Identifier: Apache-2.0
// ICC profiles through lcms2: converting a file's encoded colour into the engine's working space
// and back.
//
// The working space (docs/architecture.md, "Images"): linear light, Rec.709/sRGB primaries
// R(0.64, 0.33) G(0.30, 0.60) B(0.15, 0.06), white D65 (0.3127, 0.3290); grey images hold
// linear luminance with the same white.
//
// Values are interleaved floats; encoded values are the file's numbers scaled to 0..1 (what
// OpenImageIO hands over for integer files), with straight (unpremultiplied) colour. Alpha is
// never converted.
//
// Decisions:
// - Relative colorimetric intent: the colour a profile says a number means, adapted to the
//   working white (lcms2 adapts through its D50 connection space with Bradford, which cancels
//   between two D65 spaces). Perceptual tables would change values a viewer expects kept.
// - Float transforms without lcms2's optimisation or cache: the curves and matrices are
//   evaluated in float, so a colour outside the working gamut (Adobe RGB's pure green) comes out
//   with negative components instead of being clipped. The working profile's curves are linear
//   (gamma 1), which lcms2 extends to negative values.
// - A profile must describe the pixels: RGB for 3 colour channels, grey for 1. One lcms2 cannot
//   parse, or of another colour space (CMYK, Lab), is refused with a one-line message rather
//   than ignored: guessing sRGB would silently mislabel the colour.
#pragma once

#include "core/model/status.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace artcam {

class IccProfile {
 public:
  // `colour_channels` is 3 (RGB) or 1 (grey). Fails with "<path>: cannot read: ..." naming the
  // cause when lcms2 rejects the profile or it does not describe such pixels.
  static Result<IccProfile> fromBytes(const std::vector<unsigned char>& bytes, int colour_channels,
                                      const std::string& path);

  // Whether the profile describes CMYK colour (false when lcms2 cannot parse it).
  static bool describesCmyk(const std::vector<unsigned char>& bytes);

  // lcms2's sRGB profile, serialised: the label of files encoded in sRGB.
  static std::vector<unsigned char> srgbBytes();

  const std::vector<unsigned char>& bytes() const { return bytes_; }
  // The profile's own description ("Adobe RGB (1998)"), else "unnamed profile".
  const std::string& description() const { return description_; }
  int colourChannels() const { return colour_channels_; }

  // Whether decoding through the profile matches the sRGB curve with sRGB primaries to 1e-3 in
  // linear light over a grid of values: such files take the exact sRGB path, as untagged ones.
  bool equivalentToSrgb() const;

  // In place over `pixels` interleaved pixels of `channels` floats whose alpha is at
  // `alpha_channel` (-1: none); the colour channels must number colourChannels().
  void toWorking(float* data, size_t pixels, int channels, int alpha_channel) const;
  void fromWorking(float* data, size_t pixels, int channels, int alpha_channel) const;

 private:
  struct Transforms;
  std::vector<unsigned char> bytes_;
  std::string description_;
  int colour_channels_ = 3;
  std::shared_ptr<const Transforms> transforms_;
};

}  // namespace artcam
