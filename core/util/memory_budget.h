// SPDX-License-Identifier: Apache-2.0
// The memory one image may take, and how a size in bytes is written in a message. Every size a
// file or a command line asks for is compared with the budget before anything is allocated, so
// a request the machine cannot hold is a one-line refusal, never std::bad_alloc or the OOM
// killer.
#pragma once

#include <cstdint>
#include <string>

namespace artcam {

// ARTCAM_MAX_MEMORY_MB when set (> 0), else half of the machine's physical memory (4 GiB when
// the system does not say).
double memoryBudgetBytes();

// "12.3 MiB" below a GiB, else "1.5 GiB".
std::string describeBytes(double bytes);

// "not enough memory for 100000×100000 (149.0 GiB)": the words every allocation refusal uses,
// for an image of w×h pixels of `bytes_per_pixel` bytes.
std::string notEnoughMemoryFor(std::int64_t width, std::int64_t height, double bytes_per_pixel);

}  // namespace artcam
