// SPDX-License-Identifier: Apache-2.0
// ICC-tagged files made in the tests with lcms2 and OpenImageIO directly (not through the
// engine): an Adobe RGB (1998) profile built from its published primaries, white and gamma,
// a grey gamma profile, 16-bit files carrying them, and the profile a written file carries.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string>
#include <vector>

namespace artcam::test {

inline constexpr double kAdobeGamma = 563.0 / 256.0;
inline constexpr double kD65[2] = {0.3127, 0.3290};
inline constexpr double kAdobePrimaries[3][2] = {{0.64, 0.33}, {0.21, 0.71}, {0.15, 0.06}};
inline constexpr double kSrgbPrimaries[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};

// Adobe RGB (1998): the primaries above, D65, a pure 563/256 power curve.
std::vector<unsigned char> adobeRgbProfile();
// A grey profile with a pure power curve, described as "Grey gamma 2.2".
std::vector<unsigned char> greyGammaProfile(double gamma);
// lcms2's Lab (D50) identity profile: a valid profile of a colour space no RGB file is in.
std::vector<unsigned char> labProfile();
// A 132-byte CMYK output-class header with no tags: what lcms2 opens as a CMYK profile.
std::vector<unsigned char> cmykHeaderProfile();

void setProfile(OIIO::ImageSpec& spec, const std::vector<unsigned char>& bytes);
// The bytes of the "ICCProfile" attribute; empty when there is none.
std::vector<unsigned char> profileOf(const OIIO::ImageSpec& spec);

// A w×h 16-bit file of c channels, tagged with `icc` when it is not empty.
bool write16(const std::string& path, int w, int h, int c, const std::vector<std::uint16_t>& data,
             const std::vector<unsigned char>& icc);

}  // namespace artcam::test
