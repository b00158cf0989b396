// SPDX-License-Identifier: Apache-2.0
// A number as a message shows it: "%g" with `significant` figures (6 by default, no trailing
// zeros), the one spelling of ranges, defaults, given values and fit reports across core/ and
// the CLI.
#pragma once

#include <string>

namespace artcam {

std::string numberText(double v, int significant = 6);

}  // namespace artcam
