// SPDX-License-Identifier: Apache-2.0
// Numbers in the fits' reports and reasons (FitSummary::report, ColourFitSummary::report,
// LinesFitSummary and the "auto chose …" lines): three significant figures, as "%.3g" prints
// them, so every fit report rounds alike.
#pragma once

#include <string>

namespace artcam {

std::string threeFigures(double v);

}  // namespace artcam
