// SPDX-License-Identifier: Apache-2.0
// RGB primaries and white point as CIE 1931 xy (OpenEXR's `chromaticities` attribute), and the
// linear map between such an RGB space and the working space (linear Rec.709/sRGB primaries,
// D65 white; icc_profile.h).
//
// Decisions:
// - The map is RGB → XYZ from the primaries and white (each primary's XYZ scaled so that
//   R = G = B = 1 is the white, SMPTE RP 177), the white adapted to D65 by Bradford's cone
//   response (as lcms2 does for ICC profiles and OpenColorIO's ACES transforms do: an ACEScg
//   value converted here equals OCIO's "ACES-AP1_to_LINEAR-REC709_BFD"), then XYZ → working.
// - Linear, so it commutes with interpolation and premultiplied alpha: it is applied once on
//   read (or write), to premultiplied values, and never changes alpha.
// - Chromaticities within 1e-4 of Rec.709/D65 are Rec.709: files writing 0.3127 as a float, or
//   rounding to four digits, are not converted by a matrix a hair from the identity.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>

namespace artcam {

struct Chromaticities {
  // red x, y, green x, y, blue x, y, white x, y: OpenEXR's order.
  std::array<double, 8> xy{};

  static Chromaticities rec709();
  // Whether these describe the working space (within 1e-4).
  bool isRec709() const;
  // Whether they make an RGB space: every y > 0 and the primaries not on one line.
  bool valid() const;
  // "R(0.713, 0.293) G(0.165, 0.830) B(0.128, 0.044) W(0.3217, 0.3377)", for messages.
  std::string describe() const;
};

// Row-major 3x3 matrices on column vectors of linear RGB (valid() chromaticities only).
using Matrix3 = std::array<double, 9>;
Matrix3 workingFromChromaticities(const Chromaticities& file);
Matrix3 chromaticitiesFromWorking(const Chromaticities& file);

// The chromaticities of the RGB space whose linear values are `file_from_working` times the
// working space's (the inverse of workingFromChromaticities, its white as the map puts it: an
// adapted space's white is D65's); empty when the matrix is singular or makes no RGB space.
std::optional<Chromaticities> chromaticitiesOfMatrix(const Matrix3& file_from_working);

// In place over `pixels` interleaved pixels of `channels` floats: the first three non-alpha
// channels are R, G, B; alpha (at `alpha_channel`, -1: none) and any other channel unchanged.
void applyMatrix(const Matrix3& m, float* data, size_t pixels, int channels, int alpha_channel);

}  // namespace artcam
