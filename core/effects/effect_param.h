// SPDX-License-Identifier: Apache-2.0
// One parameter of an effect, the type both effects tables share: the image effects
// (effect_table.h) and the 3D effects of the paper's Fig 1 (effects_3d_table.h). A parameter is
// one number or a vector of N (the default's size is its type), with an inclusive range for
// every component, a unit and a meaning; the CLI's options, the studio's fields, the listings
// and the range checks are all made from it.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace artcam {

// A parameter's values: one number, or a vector of N (the default's size is the type).
using EffectValues = std::map<std::string, std::vector<double>>;

struct EffectParam {
  std::string name;           // the CLI option without "--", the panel's label: "k", "haze"
  std::string meaning;        // a few words for --help, the manual page and the panel's tooltip
  std::vector<double> value;  // the default; 1 number, or N for a vector parameter
  double min = 0, max = 0;    // inclusive, for every component
  // "" (a plain factor), "norm" (normalised frame units), "depth units", "radii" (3D: units of
  // the object frame, effects_3d_table.h).
  std::string unit;
  // A named choice (composite's operator): the value is the index of a name, min 0 and max the
  // last index; the CLI takes and writes the name, the panel a whole number.
  std::vector<std::string> choices = {};

  int size() const { return static_cast<int>(value.size()); }
  bool isChoice() const { return !choices.empty(); }
};

// "-1 … 0"; with a unit "0.01 … 10000 depth units"; a choice's names "over|under|…".
std::string rangeText(const EffectParam& param);
// "-0.15", "0.62,0.72,0.86": the default as the CLI writes it; a choice's name, "over".
std::string defaultText(const EffectParam& param);
// Empty when `value` suits the parameter, else one line naming it: "k = 0.9 is outside its
// range -1 … 0", "haze expects 3 comma-separated numbers", "op = 2.5 is not one of over|…".
std::string checkEffectValue(const EffectParam& param, const std::vector<double>& value);
// A choice parameter's value from its name or its index ("over", "0"); empty if neither.
std::optional<double> choiceValue(const EffectParam& param, const std::string& text);

// Every parameter of `params` at its default, then `values` over them, each checked: throws
// std::invalid_argument naming `effect` for a parameter it does not have or a value
// checkEffectValue refuses. What both tables' builders are handed.
EffectValues completeEffectValues(const std::string& effect, const std::vector<EffectParam>& params,
                                  const EffectValues& values);

}  // namespace artcam
