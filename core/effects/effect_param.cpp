// SPDX-License-Identifier: Apache-2.0
#include "core/effects/effect_param.h"

#include "core/util/number_text.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace artcam {

std::string rangeText(const EffectParam& param) {
  if (param.isChoice()) {
    std::string names;
    for (const std::string& n : param.choices) names += (names.empty() ? "" : "|") + n;
    return names;
  }
  std::string text = numberText(param.min) + " … " + numberText(param.max);
  return param.unit.empty() ? text : text + " " + param.unit;
}

std::string defaultText(const EffectParam& param) {
  if (param.isChoice()) return param.choices.at(static_cast<size_t>(param.value.at(0)));
  std::string text;
  for (const double v : param.value) text += (text.empty() ? "" : ",") + numberText(v);
  return text;
}

std::string checkEffectValue(const EffectParam& param, const std::vector<double>& value) {
  if (value.size() != param.value.size())
    return param.size() == 1 ? param.name + " expects one number"
                             : param.name + " expects " + std::to_string(param.size()) +
                                   " comma-separated numbers";
  for (const double v : value)
    if (!(v >= param.min && v <= param.max))  // NaN fails too
      return param.name + " = " + numberText(v) + " is outside its range " + rangeText(param);
  if (param.isChoice() && value.front() != std::floor(value.front()))
    return param.name + " = " + numberText(value.front()) + " is not one of " + rangeText(param);
  return {};
}

std::optional<double> choiceValue(const EffectParam& param, const std::string& text) {
  for (size_t i = 0; i < param.choices.size(); ++i)
    if (param.choices[i] == text) return static_cast<double>(i);
  for (size_t i = 0; i < param.choices.size(); ++i)
    if (std::to_string(i) == text) return static_cast<double>(i);
  return std::nullopt;
}

EffectValues completeEffectValues(const std::string& effect, const std::vector<EffectParam>& params,
                                  const EffectValues& values) {
  EffectValues complete;
  for (const EffectParam& p : params) complete[p.name] = p.value;
  for (const auto& [key, value] : values) {
    const EffectParam* param = nullptr;
    for (const EffectParam& p : params)
      if (p.name == key) param = &p;
    if (!param)
      throw std::invalid_argument("effect " + effect + " has no parameter \"" + key + "\"");
    if (const std::string problem = checkEffectValue(*param, value); !problem.empty())
      throw std::invalid_argument(effect + ": " + problem);
    complete[key] = value;
  }
  return complete;
}

}  // namespace artcam
