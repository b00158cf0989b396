// SPDX-License-Identifier: Apache-2.0
#include "core/fit/report_format.h"

#include "core/util/number_text.h"

namespace artcam {

std::string threeFigures(double v) { return numberText(v, 3); }

}  // namespace artcam
