// SPDX-License-Identifier: Apache-2.0
// Where the engine's run-time modules live: beside libartcam_core.so itself (the build puts them
// all in <build>/lib, the package in <libdir>/artcam), found with dladdr on the engine's own code.
#pragma once

#include <string>

namespace artcam {

// The engine library's folder with a trailing '/', or "" when the loader cannot say.
std::string engineModuleDirectory();

}  // namespace artcam
