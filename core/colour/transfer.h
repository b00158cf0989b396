// SPDX-License-Identifier: Apache-2.0
// Transfer functions between stored (encoded) values and linear light (colour is
// linear inside the engine). Exact formulas, in double:
// - sRGB (IEC 61966-2-1): v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055)^2.4
// - Rec709 (ITU-R BT.709 OETF): v < 0.081 ? v / 4.5 : ((v + 0.099) / 1.099)^(1/0.45)
// - GammaCorrected g: v^g
// Negative values are mirrored (f(-v) = -f(v)) so out-of-gamut float data survives.
// Names follow OpenImageIO's "oiio:ColorSpace" attribute ("sRGB", "Linear", "Rec709",
// "GammaCorrected2.2").
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace artcam {

struct Transfer {
  enum class Kind { Linear, Srgb, Rec709, Gamma };
  Kind kind = Kind::Linear;
  double gamma = 1.0;  // Gamma only

  static Transfer linear() { return {Kind::Linear, 1.0}; }
  static Transfer srgb() { return {Kind::Srgb, 1.0}; }
  // Empty for names we do not know (the caller then picks by pixel type).
  static std::optional<Transfer> fromColourSpace(std::string_view name);
  std::string colourSpaceName() const;

  double decode(double encoded) const;  // stored value -> linear light
  double encode(double linear) const;   // linear light -> stored value

  bool operator==(const Transfer&) const = default;
};

}  // namespace artcam
