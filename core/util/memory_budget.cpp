// SPDX-License-Identifier: Apache-2.0
#include "core/util/memory_budget.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

namespace artcam {

double memoryBudgetBytes() {
  if (const char* text = std::getenv("ARTCAM_MAX_MEMORY_MB"); text && *text) {
    char* end = nullptr;
    const double mb = std::strtod(text, &end);
    if (end && *end == '\0' && mb > 0.0 && std::isfinite(mb)) return mb * 1024.0 * 1024.0;
  }
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 4.0 * 1024.0 * 1024.0 * 1024.0;  // unknown: 4 GiB
  return 0.5 * static_cast<double>(pages) * static_cast<double>(page);
}

std::string describeBytes(double bytes) {
  char text[48];
  if (bytes < 1024.0 * 1024.0 * 1024.0)
    std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1024.0 * 1024.0));
  else
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return text;
}

std::string notEnoughMemoryFor(std::int64_t width, std::int64_t height, double bytes_per_pixel) {
  const double bytes = static_cast<double>(width) * static_cast<double>(height) * bytes_per_pixel;
  return "not enough memory for " + std::to_string(width) + "×" + std::to_string(height) + " (" +
         describeBytes(bytes) + ")";
}

}  // namespace artcam
