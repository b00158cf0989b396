// SPDX-License-Identifier: Apache-2.0
#include "core/fit/report_format.h"

#include <cstdio>

namespace artcam {

std::string threeFigures(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace artcam
