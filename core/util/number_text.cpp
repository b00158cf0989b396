// SPDX-License-Identifier: Apache-2.0
#include "core/util/number_text.h"

#include <cstdio>

namespace artcam {

std::string numberText(double v, int significant) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

}  // namespace artcam
