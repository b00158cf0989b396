// SPDX-License-Identifier: Apache-2.0
#include "core/colour/transfer.h"

#include <charconv>
#include <cmath>

namespace artcam {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c);
  return out;
}

double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
double srgbEncode(double l) {
  return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}
double rec709Decode(double v) {
  return v < 0.081 ? v / 4.5 : std::pow((v + 0.099) / 1.099, 1.0 / 0.45);
}
double rec709Encode(double l) { return l < 0.018 ? 4.5 * l : 1.099 * std::pow(l, 0.45) - 0.099; }

template <class F>
double mirrored(double v, F f) {
  return v < 0.0 ? -f(-v) : f(v);
}

}  // namespace

std::optional<Transfer> Transfer::fromColourSpace(std::string_view name) {
  const std::string s = lower(name);
  if (s.empty()) return std::nullopt;
  if (s == "linear" || s == "lin_srgb" || s == "lin_rec709" || s == "scene_linear" || s == "raw" ||
      s.rfind("linear", 0) == 0 || s == "acescg")
    return linear();
  if (s == "srgb" || s == "srgb_texture" || s == "srgb_rec709_display" || s == "srgb texture")
    return srgb();
  if (s == "rec709") return Transfer{Kind::Rec709, 1.0};
  for (const std::string_view prefix : {"gammacorrected", "gamma"}) {
    if (s.rfind(prefix, 0) != 0) continue;
    double g = 0.0;
    const char* begin = s.data() + prefix.size();
    const auto [end, error] = std::from_chars(begin, s.data() + s.size(), g);
    if (error == std::errc() && end == s.data() + s.size() && g > 0.0 && std::isfinite(g))
      return g == 1.0 ? linear() : Transfer{Kind::Gamma, g};
  }
  return std::nullopt;
}

std::string Transfer::colourSpaceName() const {
  switch (kind) {
    case Kind::Linear:
      return "Linear";
    case Kind::Srgb:
      return "sRGB";
    case Kind::Rec709:
      return "Rec709";
    case Kind::Gamma: {
      char buffer[32];
      const auto result = std::to_chars(buffer, buffer + sizeof buffer, gamma);
      return "GammaCorrected" + std::string(buffer, result.ptr);
    }
  }
  return "Linear";
}

double Transfer::decode(double v) const {
  switch (kind) {
    case Kind::Linear:
      return v;
    case Kind::Srgb:
      return mirrored(v, srgbDecode);
    case Kind::Rec709:
      return mirrored(v, rec709Decode);
    case Kind::Gamma:
      return mirrored(v, [g = gamma](double x) { return std::pow(x, g); });
  }
  return v;
}

double Transfer::encode(double l) const {
  switch (kind) {
    case Kind::Linear:
      return l;
    case Kind::Srgb:
      return mirrored(l, srgbEncode);
    case Kind::Rec709:
      return mirrored(l, rec709Encode);
    case Kind::Gamma:
      return mirrored(l, [g = gamma](double x) { return std::pow(x, 1.0 / g); });
  }
  return l;
}

}  // namespace artcam
