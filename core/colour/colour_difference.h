// SPDX-License-Identifier: Apache-2.0
// Colour differences as people see them: linear-light RGB → CIE XYZ → CIELAB → CIEDE2000.
//
// Conventions:
// - RGB is LINEAR light with the sRGB / Rec. 709 primaries and D65 white (IEC 61966-2-1), the
//   engine's working space; 1 = diffuse white. Values outside [0, 1] are allowed.
// - XYZ is scaled so the RGB white (1, 1, 1) has Y = 1, and CIELAB's reference white is that
//   same white, so (1, 1, 1) is L* = 100, a* = b* = 0 up to round-off.
// - CIEDE2000 follows CIE 142-2001 as written out by Sharma, Wu & Dalal, "The CIEDE2000
//   colour-difference formula: implementation notes, supplementary test data, and mathematical
//   observations", Color Res. Appl. 30(1), 2005, with k_L = k_C = k_H = 1; their 34 test pairs
//   are in tests/core/colour/test_colour_difference.cpp.
// Every function is total: finite input gives a finite, non-negative difference (no NaN).
#pragma once

#include <Eigen/Core>

namespace artcam {

struct Lab {
  double l = 0.0;  // L*, 0 (black) … 100 (white)
  double a = 0.0;  // a*, green − … red +
  double b = 0.0;  // b*, blue − … yellow +
};

Eigen::Vector3d xyzFromLinearRgb(const Eigen::Vector3d& rgb);
Lab labFromXyz(const Eigen::Vector3d& xyz);
Lab labFromLinearRgb(const Eigen::Vector3d& rgb);

// ΔE00 between two CIELAB colours (symmetric in its arguments).
double ciede2000(const Lab& first, const Lab& second);
// ΔE00 between two linear-light RGB colours.
double deltaE2000(const Eigen::Vector3d& rgb_first, const Eigen::Vector3d& rgb_second);

}  // namespace artcam
