// SPDX-License-Identifier: Apache-2.0
// The memory one image may take, and how a size in bytes is written in a message. Every size a
// file or a command line asks for is compared with the budget before anything is allocated, so
// a request the machine cannot hold is a one-line refusal, never std::bad_alloc or the OOM
// killer.
#pragma once

#include <cstdint>
#include <string>

namespace artcam {

// ARTCAM_MAX_MEMORY_MB (MiB) when set to a number > 0, else half of the machine's physical memory
// (4 GiB when the system does not say), or half of the process's cgroup memory.max when that is
// smaller (a farm slot, a container: slot_limits.h).
double memoryBudgetBytes();

// "the memory budget of 11.6 GiB (half this machine's memory; ARTCAM_MAX_MEMORY_MB sets it)",
// or "… of 50.0 MiB (ARTCAM_MAX_MEMORY_MB)" when the variable set it: what a refusal names.
std::string describeMemoryBudget();

// "" when ARTCAM_MAX_MEMORY_MB is unset or a number of MiB > 0; else one line naming the
// variable and its value: "ARTCAM_MAX_MEMORY_MB=abc: expected a number of MiB greater than 0
// (unset it for half this machine's memory)". The budget ignores such a value; programs report
// it once at start (the CLI refuses to run, the studio warns).
std::string memoryBudgetProblem();

// "12.3 MiB" below a GiB, else "1.5 GiB".
std::string describeBytes(double bytes);

// "not enough memory for 100000×100000 (149.0 GiB)": the words every allocation refusal uses,
// for an image of w×h pixels of `bytes_per_pixel` bytes.
std::string notEnoughMemoryFor(std::int64_t width, std::int64_t height, double bytes_per_pixel);

}  // namespace artcam
