// SPDX-License-Identifier: Apache-2.0
#include "core/util/number_text.h"

#include <cstdio>

namespace artcam {

std::string numberText(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace artcam
