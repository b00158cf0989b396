// SPDX-License-Identifier: Apache-2.0
#include "app/cli/memory.h"

#include "app/cli/commands.h"
#include "core/util/memory_budget.h"

#include <cstdint>

namespace artcam::cli {
namespace {

// The largest image this run asked for (one command per process).
FrameSize g_largest{0, 0};
double g_bytes_per_pixel = 16.0;

}  // namespace

void checkImageMemory(FrameSize size, const std::string& option, double bytes_per_pixel) {
  const double bytes =
      static_cast<double>(size.width) * static_cast<double>(size.height) * bytes_per_pixel;
  if (static_cast<double>(size.width) * static_cast<double>(size.height) >
      static_cast<double>(g_largest.width) * static_cast<double>(g_largest.height)) {
    g_largest = size;
    g_bytes_per_pixel = bytes_per_pixel;
  }
  const double budget = memoryBudgetBytes();
  if (bytes > budget)
    throw CommandError(option + " " + std::to_string(size.width) + "x" +
                       std::to_string(size.height) + ": " +
                       notEnoughMemoryFor(size.width, size.height, bytes_per_pixel) +
                       "; the budget is " + describeBytes(budget) +
                       " (half the machine's memory, or ARTCAM_MAX_MEMORY_MB)");
}

std::string allocationFailureMessage() {
  if (g_largest.width <= 0) return "not enough memory for this run";
  return notEnoughMemoryFor(g_largest.width, g_largest.height, g_bytes_per_pixel);
}

}  // namespace artcam::cli
