// SPDX-License-Identifier: Apache-2.0
// A number as a message shows it: "%g" (six significant figures, no trailing zeros), the one
// spelling of ranges, defaults and given values in refusals across core/ and the CLI.
#pragma once

#include <string>

namespace artcam {

std::string numberText(double v);

}  // namespace artcam
