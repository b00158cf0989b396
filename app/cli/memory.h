// SPDX-License-Identifier: Apache-2.0
// Memory a command line asks for. A --size the machine cannot hold is refused before the work
// starts ("not enough memory for W×H (N GiB)", core/util/memory_budget.h), and an allocation
// that still fails later is reported in the same words by the dispatcher instead of the
// standard library's "std::bad_alloc".
#pragma once

#include "core/model/camera.h"

#include <string>

namespace artcam::cli {

// Throws CommandError "OPTION WxH: not enough memory for W×H (N GiB; the budget is M)" when an
// image of `size` at `bytes_per_pixel` exceeds the memory budget. Records the size for
// allocationFailureMessage() either way. 16 bytes per pixel: float RGBA, what renders hold.
void checkImageMemory(FrameSize size, const std::string& option, double bytes_per_pixel = 16.0);

// What the dispatcher prints when std::bad_alloc or std::length_error escapes a command: the
// largest size checkImageMemory saw, or the plain words when none was.
std::string allocationFailureMessage();

}  // namespace artcam::cli
